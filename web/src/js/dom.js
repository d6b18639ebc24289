// Small DOM builders for the pages (no framework: the pages are a few tables and plots).

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

