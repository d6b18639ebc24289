// How the pages write figures and times, in one place: a figure to the digits its uncertainty
// supports (U to two significant digits, the value rounded at U's last digit, as GUM 7.2.6
// advises), and times to the second in UTC (run ids and results carry microseconds no reader
// needs).
import { el, num } from './dom.js';

// The decimals that show U to two significant digits (negative: U is 100 or more).
function decimalsOf(u) {
  let e = Math.floor(Math.log10(u));
  // 0.0996 rounds to 0.10 at two digits: one decimal fewer.
  if (Math.round(u / 10 ** (e - 1)) >= 100) e += 1;
  return 1 - e;
}

function fixed(value, decimals) {
  if (decimals >= 0) return value.toFixed(Math.min(decimals, 20));
  const step = 10 ** -decimals;
  return String(Math.round(value / step) * step);
}

// "5.70 ± 0.12" (value and U as numbers; U null, 0 or not finite: the value alone, 4 digits).
export function plusMinus(value, expanded) {
  if (value == null || !Number.isFinite(Number(value))) return '–';
  const v = Number(value);
  const u = Number(expanded);
  if (expanded == null || !Number.isFinite(u) || u <= 0) return num(v);
  const d = decimalsOf(u);
  return `${fixed(v, d)} ± ${fixed(u, d)}`;
}

// The value alone, rounded where plusMinus would round it.
export function valueAtUncertainty(value, expanded) {
  return plusMinus(value, expanded).split(' ± ')[0];
}

// A figure of results.json with its expanded uncertainty beside it (object.uncertainty[key]:
// expanded, k, combined_standard, budget), as "5.70 ± 0.12"; hover or click shows the budget.
export function uncertain(object, key) {
  const value = object ? object[key] : null;
  const u = object && object.uncertainty ? object.uncertainty[key] : null;
  if (!u || typeof u !== 'object' || u.expanded == null) return num(value);
  const budget = Array.isArray(u.budget) ? u.budget : [];
  const title = `U = ${num(u.expanded, 2)} (k = ${u.k ?? 2}), u_c = ${num(u.combined_standard, 2)}\n` +
    budget.map((c) => `${c.source} (${c.type}): u = ${num(c.standard, 2)}`).join('\n');
  const details = el('table', { class: 'budget', hidden: true },
    el('tbody', {}, budget.map((c) => el('tr', {},
      el('td', {}, c.source), el('td', {}, c.type), el('td', { class: 'n' }, num(c.standard, 2))))));
  const shown = el('span', {
    class: 'uncertain', title, tabindex: '0', role: 'button', 'aria-expanded': 'false',
    'data-expanded': String(u.expanded),
  }, plusMinus(value, u.expanded));
  const toggle = () => {
    details.hidden = !details.hidden;
    shown.setAttribute('aria-expanded', String(!details.hidden));
  };
  shown.addEventListener('click', toggle);
  shown.addEventListener('keydown', (e) => { if (e.key === 'Enter' || e.key === ' ') { e.preventDefault(); toggle(); } });
  return el('span', { class: 'uncertain-figure' }, shown, details);
}

// An UncertainFigure object ({value, expanded}) as "value ± U".
export function figureText(f) {
  if (!f || f.value == null) return '–';
  return plusMinus(f.value, f.expanded);
}

// "2026-11-27 14:33:47 UTC" from an ISO time or a run id (20261127T143347.123456Z).
export function utcSeconds(text) {
  if (!text) return '–';
  const s = String(text);
  const id = /^(\d{4})(\d{2})(\d{2})T(\d{2})(\d{2})(\d{2})/.exec(s);
  if (id) return `${id[1]}-${id[2]}-${id[3]} ${id[4]}:${id[5]}:${id[6]} UTC`;
  const iso = /^(\d{4}-\d{2}-\d{2})[T ](\d{2}:\d{2}:\d{2})/.exec(s);
  return iso ? `${iso[1]} ${iso[2]} UTC` : s;
}

// A limit check's figure name and unit, from the verdict table's declaration carried in
// results.json (older runs: the limit key and its unit).
export function limitName(c) {
  const unit = c.display_unit || (c.unit || '').replace('N*m', 'N·m');
  return `${c.name || c.limit}${unit ? ` [${unit}]` : ''}`;
}

// Where in the run a limit check's figure was measured: "static[1] reverse 60 N·m" → "reverse,
// 60 N·m"; a figure of the whole run (no array element) → "whole run".
export function whereText(c) {
  const w = String(c.what || '').replace(/^[a-z_.]+(\[\d+\])?\s*/i, '').trim();
  return w ? w.replace(/ (-?[\d.]+ N·m)$/, ', $1') : 'whole run';
}
