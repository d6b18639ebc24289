// Compare runs (/compare?ids=a,b,...): their static TE curves, lost-motion curves and dynamic
// TE order spectra on one plot each, one colour per run (two units, or one unit before and
// after run-in). Sections come from each run's results.json keys (docs/formats/results.md).
import { el, num, table, section, verdictOf, specName } from './dom.js';
import { makePlot, joinSeries, palette } from './plots.js';
import { uncertain, figureText, utcSeconds } from './figures.js';
import { readRun } from './run_reads.js';

const main = document.getElementById('compare');
const message = document.getElementById('message');
const ids = (new URLSearchParams(location.search).get('ids') || '').split(',').map((s) => s.trim()).filter(Boolean);

const maxOf = (values) => {
  const finite = values.filter((v) => v != null && Number.isFinite(v));
  return finite.length ? Math.max(...finite) : null;
};

function label(run) {
  return `${run.unit_serial || '?'} ${utcSeconds(run.started_at || run.id).replace(' UTC', '')}`;
}

// Figures with their expanded uncertainty (k = 2), as the run page shows them: two units are
// told apart only where their intervals are.
function staticP2pMax(results) {
  const entries = (results.static || []).filter((p) => p.p2p_arcmin != null && Number.isFinite(p.p2p_arcmin));
  if (!entries.length) return '–';
  const largest = entries.reduce((a, b) => (b.p2p_arcmin > a.p2p_arcmin ? b : a));
  return uncertain(largest, 'p2p_arcmin');
}

function lostMotion(results) {
  // The catalogues' figure (locked output) first, then the brake ladder's fit.
  const t = results.torsional && results.torsional.lost_motion_arcmin;
  if (t && t.value != null) return figureText(t);
  if (results.lost_motion_fit) return uncertain(results.lost_motion_fit, 'lost_motion_arcmin');
  return num(maxOf((results.lost_motion || []).map((l) => l.max_arcmin)));
}

function summary(runs) {
  return section('summary', 'Runs',
    table([
      { label: '', value: (r) => el('span', { class: 'swatch', style: `background:${r.color}` }) },
      { label: 'Run', value: (r) => el('a', { href: `/run?id=${encodeURIComponent(r.run.id)}` }, r.run.id) },
      { label: 'Unit', value: (r) => r.run.unit_serial || '–' },
      { label: 'Procedure', value: (r) => r.run.procedure },
      { label: 'Spec', value: (r) => specName(r.run, r.results) || '–' },
      { label: 'Verdict', value: (r) => verdictOf(r.run, r.results) || '–' },
      { label: 'Static TE p2p max ± U [arcmin]', value: (r) => staticP2pMax(r.results), class: 'n' },
      { label: 'Lost motion ± U [arcmin]', value: (r) => lostMotion(r.results), class: 'n' },
      { label: 'Dynamic TE p2p ± U [arcsec]', value: (r) => (r.results.dynamic ? uncertain(r.results.dynamic, 'p2p_arcsec') : '–'), class: 'n' },
    ], runs, { id: 'compare-table' }));
}

function plotSection(id, title, caption) {
  const area = el('div', { class: 'plot-area' });
  const s = section(id, title, el('figure', { class: 'plot', id: `${id}-plot` }, el('figcaption', {}, caption), area));
  return { s, area };
}

async function main_() {
  if (ids.length < 2) throw new Error('Pick two or more runs in the history to compare (/compare?ids=a,b).');
  if (ids.length > 12) throw new Error(`${ids.length} runs: compare at most 12 at once.`);
  // Queued, two at a time, a busy answer retried (run_reads.js): any number of runs loads.
  let loaded = 0;
  message.textContent = `Loading ${ids.length} runs…`;
  const details = await Promise.all(ids.map((id) => readRun(`/api/runs/${encodeURIComponent(id)}`).then((d) => {
    loaded += 1;
    message.textContent = `Loading runs: ${loaded} of ${ids.length}…`;
    return d;
  })));
  const runs = details.map((d, i) => ({ run: d.run, results: d.results || {}, color: palette[i % palette.length] }));
  message.hidden = true;
  main.append(summary(runs));
  const draws = [];

  const statics = runs.filter((r) => Array.isArray(r.results.static) && r.results.static.length);
  if (statics.length) {
    const { s, area } = plotSection('static', 'Static TE', 'Static TE against output angle; solid forward, dashed reverse');
    main.append(s);
    const pairs = [];
    const series = [];
    for (const r of statics) {
      for (const p of r.results.static) {
        pairs.push([p.points.map((q) => q.output_angle_deg), p.points.map((q) => q.te_arcmin)]);
        series.push({ label: `${label(r.run)}: ${p.direction} ${num(p.load_nm, 3)} N·m`, color: r.color, points: true, line: true, spanGaps: true, dash: p.direction === 'reverse' ? [6, 3] : undefined });
      }
    }
    draws.push(() => makePlot(area, { xLabel: 'output angle [deg]', yLabel: 'TE [arcmin]', series, data: joinSeries(pairs) }));
  }

  const lostMotion = runs.filter((r) => (Array.isArray(r.results.lost_motion) && r.results.lost_motion.length) || r.results.lost_motion_fit);
  const perPosition = lostMotion.filter((r) => Array.isArray(r.results.lost_motion));
  if (perPosition.length) {
    const { s, area } = plotSection('lost-motion', 'Lost motion (static test)', '|Reverse − forward| TE per output position, per load (a width)');
    main.append(s);
    const pairs = [];
    const series = [];
    for (const r of perPosition) {
      const n = r.results.options && r.results.options.positions;
      for (const l of r.results.lost_motion) {
        pairs.push([l.positions.map((p) => (n ? (p * 360) / n : p)), l.lost_motion_arcmin]);
        series.push({ label: `${label(r.run)}: ${num(l.load_nm, 3)} N·m`, color: r.color, points: true, line: true, spanGaps: true });
      }
    }
    draws.push(() => makePlot(area, { xLabel: 'output angle [deg]', yLabel: 'lost motion [arcmin]', series, data: joinSeries(pairs) }));
  }
  const fits = lostMotion.filter((r) => r.results.lost_motion_fit);
  if (fits.length) {
    const { s, area } = plotSection('torque-twist', 'Lost motion and stiffness', 'Torque against twist (lost-motion runs)');
    main.append(s);
    const pairs = [];
    const series = [];
    for (const r of fits) {
      for (const travel of [1, -1]) {
        const pts = (r.results.lost_motion_fit.points || []).filter((p) => p.travel === travel);
        pairs.push([pts.map((p) => p.twist_arcmin), pts.map((p) => p.torque_nm)]);
        series.push({ label: `${label(r.run)}: ${travel > 0 ? 'forward' : 'reverse'}`, color: r.color, points: true, dash: travel < 0 ? [6, 3] : undefined });
      }
    }
    draws.push(() => makePlot(area, { xLabel: 'twist [arcmin]', yLabel: 'torque [N·m]', series, data: joinSeries(pairs) }));
  }

  const dynamics = runs.filter((r) => r.results.dynamic && r.results.dynamic.order_spectrum);
  if (dynamics.length) {
    const { s, area } = plotSection('spectrum', 'Dynamic TE order spectra', 'TE amplitude against output order');
    main.append(s);
    const pairs = dynamics.map((r) => {
      const sp = r.results.dynamic.order_spectrum;
      return [sp.order_output, sp.amplitude_arcsec.map((a) => (a > 0 ? a : null))];
    });
    const series = dynamics.map((r) => ({ label: `${label(r.run)} (p2p ${num(r.results.dynamic.p2p_arcsec)} arcsec)`, color: r.color, spanGaps: true }));
    draws.push(() => makePlot(area, { xLabel: 'output order', yLabel: 'amplitude [arcsec]', logY: true, series, data: joinSeries(pairs) }));
  }
  if (!draws.length) main.append(el('p', { class: 'message' }, 'These runs have no static, lost-motion or dynamic results to plot.'));
  for (const draw of draws) draw();
  document.body.dataset.ready = 'true';
}

main_().catch((e) => {
  message.hidden = false;
  message.className = 'message error';
  message.textContent = e.message || String(e);
});
