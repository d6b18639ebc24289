// Small DOM builders for the pages (no framework: the pages are a few tables and plots).
import { roundedToUncertainty } from './uncertain_digits.js';

export function el(tag, attrs = {}, ...children) {
  const node = document.createElement(tag);
  for (const [key, value] of Object.entries(attrs || {})) {
    if (value == null || value === false) continue;
    if (key === 'class') node.className = value;
    else if (key === 'text') node.textContent = value;
    else if (key.startsWith('on')) node.addEventListener(key.slice(2), value);
    else node.setAttribute(key, value === true ? '' : value);
  }
  for (const child of children.flat()) {
    if (child == null || child === false) continue;
    node.append(child instanceof Node ? child : document.createTextNode(String(child)));
  }
  return node;
}

// A number for a table: fixed significant digits, '–' for null (not computed).
export function num(value, digits = 4) {
  if (value == null || !Number.isFinite(Number(value))) return '–';
  const v = Number(value);
  if (v !== 0 && (Math.abs(v) >= 1e6 || Math.abs(v) < 1e-3)) return v.toExponential(digits - 1);
  return Number(v.toPrecision(digits)).toString();
}

// columns: [{label, value: (row) => text or Node, class?}]
export function table(columns, rows, attrs = {}) {
  return el('table', attrs,
    el('thead', {}, el('tr', {}, columns.map((c) => el('th', { class: c.class }, c.label)))),
    el('tbody', {}, rows.map((r) => el('tr', {}, columns.map((c) => el('td', { class: c.class }, c.value(r)))))));
}

export function section(id, title, ...children) {
  return el('section', { id, class: 'block' }, el('h2', {}, title), ...children);
}

// The verdict of a run: PASS, FAIL or UNDECIDED (a limit inside a figure's uncertainty
// interval, ISO 14253-1) as recorded; runs from before the verdict field by their pass.
export function verdictOf(run, results) {
  const v = (run && run.verdict) ?? (results && results.verdict);
  if (v === 'PASS' || v === 'FAIL' || v === 'UNDECIDED') return v;
  const pass = (results && results.pass) ?? (run && run.pass);
  if (pass === true) return 'PASS';
  if (pass === false) return 'FAIL';
  return null;
}

export function specName(run, results) {
  const s = (run && run.spec) ?? (results && results.spec);
  if (!s) return null;
  return typeof s === 'string' ? s : s.name || s.model || null;
}

// "value ± U" to the digits U supports (uncertain_digits.js); `digits` significant without U.
function figureText(value, expanded, digits) {
  const r = roundedToUncertainty(value, expanded);
  return r ? `${r.value} ± ${r.expanded}` : `${num(value, digits)} ± ${num(expanded, 2)}`;
}

// A figure of results.json with its expanded uncertainty: "5.70 ± 0.02" and, on hover or
// focus, its budget (the figure's `uncertainty` entry beside it: value, expanded, k, budget).
// Click opens the budget as a small table under the value. A figure without one shows alone.
export function uncertain(object, key, digits = 4) {
  const value = object ? object[key] : null;
  const u = object && object.uncertainty ? object.uncertainty[key] : null;
  if (!u || typeof u !== 'object' || u.expanded == null) return num(value, digits);
  const budget = Array.isArray(u.budget) ? u.budget : [];
  const title = `U = ${num(u.expanded, 2)} (k = ${u.k ?? 2}), u_c = ${num(u.combined_standard, 2)}\n` +
    budget.map((c) => `${c.source} (${c.type}): u = ${num(c.standard, 2)}`).join('\n');
  const details = el('table', { class: 'budget', hidden: true },
    el('tbody', {}, budget.map((c) => el('tr', {},
      el('td', {}, c.source), el('td', {}, c.type), el('td', { class: 'n' }, num(c.standard, 2))))));
  const shown = el('span', {
    class: 'uncertain', title, tabindex: '0', role: 'button', 'aria-expanded': 'false',
    'data-expanded': String(u.expanded),
  }, figureText(value, u.expanded, digits));
  const toggle = () => {
    details.hidden = !details.hidden;
    shown.setAttribute('aria-expanded', String(!details.hidden));
  };
  shown.addEventListener('click', toggle);
  shown.addEventListener('keydown', (e) => { if (e.key === 'Enter' || e.key === ' ') { e.preventDefault(); toggle(); } });
  return el('span', { class: 'uncertain-figure' }, shown, details);
}
