// The run page's figure table, drawn from the figures the procedure declares (GET
// /api/procedures: each procedure's "figures", generated from src/figures): a newly declared
// figure appears here without an edit to this file. A declaration's path reads results.json
// as the verdict reads it: keys separated by dots, `name[*]` every element of an array; the
// uncertainty beside a figure (its object's `uncertainty[key]`) or in the figure object.
import { el, section, table } from './dom.js';
import { plusMinus } from './figures.js';

function elementLabel(e) {
  if (!e || typeof e !== 'object') return '';
  const parts = [];
  if (typeof e.direction === 'string') parts.push(e.direction);
  if (typeof e.name === 'string') parts.push(e.name);
  if (typeof e.load_nm === 'number') parts.push(`${e.load_nm} N·m`);
  return parts.join(' ');
}

// Every place `path` reaches: { where, value, expanded }.
export function figureValues(results, path) {
  const out = [];
  const parts = String(path).split('.');
  const walk = (node, i, where) => {
    if (!node || typeof node !== 'object' || Array.isArray(node)) return;
    let key = parts[i];
    const every = key.endsWith('[*]');
    if (every) key = key.slice(0, -3);
    if (!(key in node)) return;
    const item = node[key];
    if (every) {
      if (!Array.isArray(item) || i + 1 >= parts.length) return;
      item.forEach((e) => walk(e, i + 1, elementLabel(e)));
      return;
    }
    if (i + 1 < parts.length) { walk(item, i + 1, where); return; }
    const beside = node.uncertainty && typeof node.uncertainty === 'object' ? node.uncertainty[key] : null;
    const own = item && typeof item === 'object' ? item : null;
    const value = own ? own.value : item;
    if (typeof value !== 'number') return;
    const u = beside && typeof beside === 'object' ? beside.expanded : own ? own.expanded : null;
    out.push({ where, value, expanded: typeof u === 'number' ? u : null });
  };
  walk(results, 0, '');
  return out;
}

// One row per declared figure found in `results` (per array element for a per-element one).
export function declaredFigureRows(declarations, results) {
  const rows = [];
  for (const d of declarations || []) {
    const scale = Number(d.display_scale) || 1;
    for (const v of figureValues(results, d.path)) {
      rows.push({
        name: d.name,
        label: d.label,
        where: v.where,
        value: plusMinus(v.value * scale, v.expanded == null ? null : v.expanded * scale),
        unit: d.display_unit,
        limit: d.limit ? d.limit.key : '',
        fleet: d.fleet ? d.fleet.name : '',
      });
    }
  }
  return rows;
}

export function declaredFiguresSection(declarations, results) {
  const rows = declaredFigureRows(declarations, results);
  if (!rows.length) return null;
  return section('figures', 'Figures',
    table([
      { label: 'Figure', value: (r) => el('span', { title: r.name }, r.label) },
      { label: 'Measured at', value: (r) => r.where || '' },
      { label: 'Value ± U (k = 2)', value: (r) => r.value, class: 'n' },
      { label: 'Unit', value: (r) => r.unit },
      { label: 'Spec limit', value: (r) => r.limit || '–' },
      { label: 'Fleet trend', value: (r) => r.fleet || '–' },
    ], rows, { id: 'figure-table' }));
}

// The declarations of `procedure` from GET /api/procedures (none from an older daemon).
export async function declaredFiguresOf(get, procedure) {
  try {
    const list = (await get('/api/procedures')).procedures || [];
    const p = list.find((x) => x.name === procedure);
    return p && Array.isArray(p.figures) ? p.figures : [];
  } catch (_) {
    return [];
  }
}
