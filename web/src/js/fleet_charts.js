// The fleet page's answer drawn: the trend (one colour per bench, x the run's start date), the
// SPC table and the individuals chart with its control limits (mean ± 2.66 MR-bar) and the
// spec limits, from GET /api/fleet/spc (docs/api.md). Points outside the spec limits are
// marked (a red ring) on both charts.
import { el, num, table, section } from './dom.js';
import { makePlot, joinSeries, palette } from './plots.js';
import { utcSeconds } from './figures.js';

// Fewer runs than this: capability indices are too uncertain to act on (the usual rule of
// thumb for a first capability study is 25 or more subgroups).
export const SPC_MIN_RUNS = 25;

const OUT_OF_SPEC = '#b3261e';

function outOfSpec(answer, v) {
  const lim = answer.limits || {};
  return v != null && ((lim.upper != null && v > lim.upper) || (lim.lower != null && v < lim.lower));
}

const epochSeconds = (p) => Date.parse(p.started_at) / 1000;

// The unit sequence is counted: whole ticks only.
const WHOLE = [1, 2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000, 5000, 10000, 20000, 50000, 100000];

function when(point) {
  return utcSeconds(point.started_at).replace(' UTC', '');
}

function plotFigure(id, caption, points) {
  const area = el('div', { class: 'plot-area' });
  const figure = el('figure', { class: 'plot', id, 'data-points': String(points) },
    el('figcaption', {}, caption), area);
  return { figure, area };
}

// One series per bench, points only: a bench that drifts stands apart.
export function trendSection(answer, figure, model) {
  const benches = [...new Set(answer.points.map((p) => p.bench))].sort();
  const pairs = benches.map((b) => {
    const mine = answer.points.filter((p) => p.bench === b);
    return [mine.map(epochSeconds), mine.map((p) => p.value)];
  });
  const series = benches.map((b, i) => ({ label: b, color: palette[i % palette.length], points: true }));
  const outside = answer.points.filter((p) => outOfSpec(answer, p.value));
  if (outside.length) {
    pairs.push([outside.map(epochSeconds), outside.map((p) => p.value)]);
    series.push({ label: `out of spec (${outside.length})`, color: OUT_OF_SPEC, points: true, marker: 'ring' });
  }
  const { figure: fig, area } = plotFigure('trend-plot',
    `${figure.name} [${figure.unit}] of ${model} against the run's start (UTC); one colour per bench${outside.length ? '; out of spec: red rings' : ''}`, answer.points.length);
  fig.dataset.outOfSpec = String(outside.length);
  const s = section('trend', `Trend (${answer.points.length} runs, ${benches.length} ${benches.length === 1 ? 'bench' : 'benches'})`, fig);
  const draw = () => makePlot(area, { xLabel: 'run started (UTC)', yLabel: `${figure.name} [${figure.unit}]`, series, data: joinSeries(pairs), xTime: true });
  return { section: s, draw };
}

// Capability indices to two decimals: a third one is noise at any realistic n.
const index = (v) => Number(v).toFixed(2);

function spcRows(answer) {
  const s = answer.spc;
  const lim = answer.limits || {};
  return [
    ['n', 'runs', s.n, (v) => String(v)],
    ['mean', 'mean (centre line)', s.mean],
    ['sigma', 'sigma, overall (n − 1)', s.sigma],
    ['mr_bar', 'MR-bar (mean moving range)', s.mr_bar],
    ['sigma_within', 'sigma within (MR-bar / 1.128)', s.sigma_within],
    ['ucl', 'UCL (mean + 2.66 MR-bar)', s.ucl],
    ['lcl', 'LCL (mean − 2.66 MR-bar)', s.lcl],
    ['lsl', `LSL (${answer.limits_from})`, lim.lower],
    ['usl', `USL (${answer.limits_from})`, lim.upper],
    ['cp', 'Cp (within)', s.cp, index],
    ['cpk', 'Cpk (within)', s.cpk, index],
    ['pp', 'Pp (overall)', s.pp, index],
    ['ppk', 'Ppk (overall)', s.ppk, index],
    ['out_of_control', 'points outside UCL/LCL', s.out_of_control.length, (v) => String(v)],
  ];
}

export function spcSection(answer, figure) {
  if (!answer.spc) {
    return { section: section('spc', 'SPC', el('p', { class: 'message', id: 'spc-empty' },
      `${answer.points.length} run${answer.points.length === 1 ? '' : 's'}: SPC needs at least 2.`)), draw: () => {} };
  }
  const rows = spcRows(answer);
  const n = answer.spc.n;
  const few = n < SPC_MIN_RUNS
    ? el('p', { class: 'fleet-warning', id: 'spc-warning', role: 'note' },
      `Only ${n} run${n === 1 ? '' : 's'}: Cp, Cpk, Pp and Ppk from fewer than ${SPC_MIN_RUNS} runs are rough estimates; do not judge the process capable or not on them.`)
    : null;
  const spcTable = el('table', { id: 'spc-table' }, el('tbody', {}, rows.map(([key, label, value, show]) =>
    el('tr', { 'data-key': key },
      el('th', {}, label),
      el('td', { class: 'n', 'data-value': value == null ? '' : String(value) },
        value == null ? '–' : (show ? show(value) : num(value, 5)))))));
  const outside = answer.spc.out_of_control.map((i) => answer.points[i]);
  const outsideTable = outside.length
    ? table([
      { label: '#', value: (p) => String(p.sequence), class: 'n' },
      { label: 'Started (UTC)', value: when },
      { label: 'Bench', value: (p) => p.bench },
      { label: 'Run', value: (p) => p.run_id },
      { label: 'Unit', value: (p) => p.unit_serial || '–' },
      { label: `${figure.name} [${figure.unit}]`, value: (p) => num(p.value, 5), class: 'n' },
    ], outside, { id: 'outside-table' })
    : el('p', { class: 'note' }, 'No point outside the control limits.');

  const x = answer.points.map((p) => p.sequence);
  const y = answer.points.map((p) => p.value);
  const flat = (v) => x.map(() => v);
  const s = answer.spc;
  const data = [x, y, flat(s.ucl), flat(s.mean), flat(s.lcl)];
  const series = [
    { label: figure.name, color: palette[0], points: true, line: true },
    { label: 'UCL', color: '#777', dash: [6, 3] },
    { label: 'CL', color: '#777' },
    { label: 'LCL', color: '#777', dash: [6, 3] },
  ];
  // A spec limit far from the process would flatten it to a line: drawn only within a span of
  // the chart's own range, else named under it.
  const lo = Math.min(s.lcl, ...y);
  const hi = Math.max(s.ucl, ...y);
  const span = Math.max(hi - lo, Math.abs(s.mean) * 1e-9);
  const notDrawn = [];
  for (const [key, label] of [['upper', 'USL'], ['lower', 'LSL']]) {
    const v = answer.limits && answer.limits[key];
    if (v == null) continue;
    if (v >= lo - span && v <= hi + span) {
      data.push(flat(v));
      series.push({ label, color: '#b3261e', dash: [2, 3], width: 2 });
    } else {
      notDrawn.push(`${label} ${num(v, 5)} ${figure.unit} (${v > hi ? 'far above' : 'far below'} the chart)`);
    }
  }
  if (outside.length) {
    const marked = new Set(s.out_of_control);
    data.push(y.map((v, i) => (marked.has(i) ? v : null)));
    series.push({ label: 'outside control limits', color: '#c77700', points: true });
  }
  const specOut = y.map((v) => (outOfSpec(answer, v) ? v : null));
  if (specOut.some((v) => v != null)) {
    data.push(specOut);
    series.push({ label: 'out of spec', color: OUT_OF_SPEC, points: true, marker: 'ring' });
  }
  const { figure: fig, area } = plotFigure('individuals-plot',
    'Individuals chart: values, centre line and control limits (dashed grey), spec limits (dotted red)', answer.points.length);
  const beyond = notDrawn.length
    ? el('p', { class: 'note', id: 'limits-not-drawn' }, `Not drawn: ${notDrawn.join(', ')}.`)
    : null;
  const sec = section('spc', 'SPC', few, spcTable, fig, beyond, el('h3', {}, 'Outside the control limits'), outsideTable);
  const draw = () => makePlot(area, { xLabel: 'run number (oldest first)', yLabel: `${figure.name} [${figure.unit}]`, series, data, xIncrs: WHOLE });
  return { section: sec, draw };
}
