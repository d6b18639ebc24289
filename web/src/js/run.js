// The run page (/run?id=...): a run's header, its tables and interactive plots, read from
// GET /api/runs/{id} by the results schema (docs/formats/results.md): each section is read
// from its own key, never guessed from its shape. Prints as an A4 test certificate.
import { el, num, table, section, verdictOf, specName } from './dom.js';
import { makePlot, joinSeries, palette } from './plots.js';
import { twinDiagnosisSection } from './twin_diagnosis.js';
import { awaitResults } from './run_progress.js';
import { uncertain, plusMinus, figureText, utcSeconds, limitName, whereText } from './figures.js';
import { readRun } from './run_reads.js';
import { exportButtons } from './run_exports.js';
import { get } from './api.js';
import { declaredFiguresOf, declaredFiguresSection } from './declared_figures.js';

const id = new URLSearchParams(location.search).get('id') || '';
const main = document.getElementById('run');
const message = document.getElementById('message');
document.getElementById('print').addEventListener('click', () => window.print());
document.getElementById('certificate').href = `/certificate?id=${encodeURIComponent(id)}`;

const plotWidth = (box) => Math.max(300, Math.min(2000, box.clientWidth || 800));

function header(run, results) {
  const verdict = verdictOf(run, results);
  const status = run.status + (run.reason ? ` – ${run.reason}` : '');
  const r = results || {};
  const fact = (label, value, cls) => [el('dt', {}, label), el('dd', { class: cls }, value ?? '–')];
  const spec = specName(run, results);
  return el('section', { class: 'run-head' },
    // On paper this page is the run's record; the certificate is a page of its own.
    el('div', { class: 'certificate-title' }, 'Transmission test record (not a certificate)'),
    el('h1', {}, `${r.procedure || run.procedure} run ${run.id}`),
    el('div', { class: 'head-grid' },
      el('dl', { class: 'facts' },
        fact('Unit', run.unit_serial || r.unit_serial),
        fact('Spec', spec ? `${spec}${r.spec && r.spec.model ? ` (${r.spec.model})` : ''}` : null),
        fact('Operator', r.operator ?? run.operator),
        fact('Bench', r.bench),
        fact('Started', utcSeconds(run.started_at)),
        fact('Finished', run.finished_at ? utcSeconds(run.finished_at) : null),
        fact('Status', status, `status-${run.status}`),
        fact('Software', r.software_version || run.software_version),
        fact('Config hash', run.config_hash ? run.config_hash.slice(0, 16) : null, 'mono'),
        fact('Gear ratio', r.gear ? num(r.gear.ratio) : null),
        fact('Repeats', Array.isArray(r.repeats) ? `${r.repeats.length} (figures are their mean; the spread is in each ± U)` : null)),
      el('div', { class: `verdict verdict-${(verdict || 'none').toLowerCase()}`, id: 'verdict',
        title: verdict === 'UNDECIDED' ? `a limit lies inside a figure's uncertainty interval; counts as ${r.undecided_counts_as || 'fail'} for acceptance` : null },
      verdict || 'no verdict')),
    exportButtons(run));
}

function limitChecks(results) {
  const checks = results.limit_checks;
  if (!Array.isArray(checks) || !checks.length) return null;
  return section('limit-checks', 'Limit checks',
    table([
      { label: 'Figure', value: (c) => el('span', { title: c.limit }, limitName(c)) },
      { label: 'Measured at', value: (c) => el('span', { title: c.path || c.what }, whereText(c)) },
      { label: 'Measured ± U (k = 2)', value: (c) => (c.uncertainty_stated !== false ? plusMinus(c.measured, c.expanded) : num(c.measured)), class: 'n' },
      { label: limitValueLabel(checks), value: (c) => num(c.value), class: 'n' },
      { label: 'Decision', value: (c) => decisionCell(c) },
    ], checks, { id: 'limit-table' }));
}

function limitValueLabel(checks) {
  return checks.some((c) => c.minimum) ? 'Limit value (min or max)' : 'Limit value';
}

// PASS / FAIL / UNDECIDED as ISO 14253-1 decides with the guard band; older runs by pass.
function decisionCell(c) {
  const d = c.decision || (c.pass === true ? 'PASS' : c.pass === false ? 'FAIL' : null);
  if (!d) return '–';
  return el('span', { class: `decision-${d.toLowerCase()}` }, d);
}

function plotBox(idName, title) {
  return el('figure', { class: 'plot', id: idName }, el('figcaption', {}, title), el('div', { class: 'plot-area' }));
}

function staticSections(results) {
  const passes = results.static;
  if (!Array.isArray(passes)) return [];
  const out = [];
  const passLabel = (p) => `${p.direction}, ${num(p.load_nm, 3)} N·m`;
  const box = plotBox('static-plot', 'Static TE against output angle, per direction and load');
  out.push(section('static', 'Static transmission error',
    table([
      { label: 'Direction', value: (p) => p.direction },
      { label: 'Load [N·m]', value: (p) => num(p.load_nm), class: 'n' },
      { label: 'Mean ± U [arcmin]', value: (p) => uncertain(p, 'mean_arcmin'), class: 'n' },
      { label: 'Peak-to-peak ± U [arcmin]', value: (p) => uncertain(p, 'p2p_arcmin'), class: 'n' },
      { label: 'Std dev ± U [arcmin]', value: (p) => uncertain(p, 'std_arcmin'), class: 'n' },
      { label: 'Positions', value: (p) => (p.points || []).length, class: 'n' },
    ], passes, { id: 'static-table' }),
    box));
  const draw = () => {
    makePlot(box.querySelector('.plot-area'), {
      xLabel: 'output angle [deg]', yLabel: 'TE [arcmin]',
      series: passes.map((p, i) => ({ label: passLabel(p), color: palette[i % palette.length], points: true, line: true, spanGaps: true, dash: p.direction === 'reverse' ? [6, 3] : undefined })),
      data: joinSeries(passes.map((p) => [p.points.map((q) => q.output_angle_deg), p.points.map((q) => q.te_arcmin)])),
    });
  };
  const lm = results.lost_motion;
  const positions = results.options && results.options.positions;
  if (Array.isArray(lm) && lm.length) {
    const lmBox = plotBox('lost-motion-plot', 'Lost motion (|reverse − forward| TE, a width) per position');
    out.push(section('lost-motion', 'Lost motion (static test)',
      table([
        { label: 'Load [N·m]', value: (l) => num(l.load_nm), class: 'n' },
        { label: 'Positions', value: (l) => (l.positions || []).length, class: 'n' },
        { label: 'Mean ± U [arcmin]', value: (l) => uncertain(l, 'mean_arcmin'), class: 'n' },
        { label: 'Max ± U [arcmin]', value: (l) => uncertain(l, 'max_arcmin'), class: 'n' },
        { label: 'Max |·| ± U [arcmin]', value: (l) => uncertain(l, 'max_abs_arcmin'), class: 'n' },
      ], lm, { id: 'lost-motion-table' }),
      lmBox));
    const drawLm = () => makePlot(lmBox.querySelector('.plot-area'), {
      xLabel: 'output angle [deg]', yLabel: 'lost motion [arcmin]',
      series: lm.map((l, i) => ({ label: `${num(l.load_nm, 3)} N·m`, color: palette[i % palette.length], points: true, line: true, spanGaps: true })),
      data: joinSeries(lm.map((l) => [l.positions.map((p) => (positions ? (p * 360) / positions : p)), l.lost_motion_arcmin])),
    });
    out.draws = [draw, drawLm];
  } else {
    out.draws = [draw];
  }
  const shift = results.load_shift;
  if (Array.isArray(shift) && shift.length) {
    out.push(section('stiffness', 'Stiffness from the load shift',
      table([
        { label: 'Direction', value: (s) => s.direction },
        { label: 'Load [N·m]', value: (s) => num(s.load_nm), class: 'n' },
        { label: 'Reference [N·m]', value: (s) => num(s.reference_load_nm), class: 'n' },
        { label: 'Shift ± U [arcmin]', value: (s) => uncertain(s, 'shift_arcmin'), class: 'n' },
        { label: 'Stiffness ± U [N·m/rad]', value: (s) => uncertain(s, 'stiffness_nm_per_rad'), class: 'n' },
      ], shift, { id: 'stiffness-table' })));
  }
  if (results.settle_timeouts) {
    out.push(el('p', { class: 'warning' }, `${results.settle_timeouts} positions measured without having settled.`));
  }
  return out;
}

// The TE (or another channel) of the stored samples against time: the whole record at first,
// fetched again at full resolution for the range the user zooms into (GET .../trace).
function traceSection(run, title, channel) {
  const box = plotBox('trace-plot', title);
  const select = el('select', { id: 'trace-channel', class: 'no-print' },
    ['te_arcsec', 'input_speed', 'torque', 'brake_current', 'brake_torque', 'theta_out']
      .map((c) => el('option', { value: c, selected: c === channel }, c)));
  const note = el('span', { class: 'note', id: 'trace-note' });
  const whole = el('button', { type: 'button', class: 'no-print small' }, 'Whole record');
  box.querySelector('figcaption').append(' ', select, ' ', whole, ' ', note);
  let u = null;
  let current = channel;
  let fetched = null;
  let seq = 0;
  const load = async (from, to) => {
    const area = box.querySelector('.plot-area');
    const columns = Math.min(4000, plotWidth(area));
    const range = from == null ? '' : `&from_s=${Math.max(0, from)}&to_s=${Math.max(0, to)}`;
    const mine = ++seq;
    const t = await readRun(`/api/runs/${encodeURIComponent(run.id)}/trace?channels=${current}&columns=${columns}${range}`);
    if (mine !== seq) return;
    fetched = [t.from_s, t.to_s];
    note.textContent = t.full_resolution ? `every sample (${t.samples_in_range})`
      : `min/max of ${t.samples_in_range} samples in ${columns} columns`;
    const data = [t.t_s, t.series[current]];
    const unit = t.channels[0] ? t.channels[0].unit : '';
    if (!u) {
      u = makePlot(area, {
        xLabel: 'time from the start of the record [s]', yLabel: `${current} [${unit}]`,
        series: [{ label: current }],
        data,
        onZoom: (min, max) => {
          // The drawn rows sit within the fetched range by a quarter column: the same view.
          const eps = fetched ? (fetched[1] - fetched[0]) * 0.01 + 1e-9 : 0;
          if (fetched && Math.abs(min - fetched[0]) <= eps && Math.abs(max - fetched[1]) <= eps) return;
          load(min, max).catch(showError);
        },
      });
    } else {
      u.setData(data, false);
    }
  };
  whole.addEventListener('click', () => {
    load().then(() => u && u.setScale('x', { min: fetched[0], max: fetched[1] })).catch(showError);
  });
  select.addEventListener('change', () => {
    current = select.value;
    if (u) { u.destroy(); u = null; }
    box.querySelector('.plot-area').replaceChildren();
    load().catch(showError);
  });
  const s = section('record', 'Record', box);
  s.draws = [() => load().catch(showError)];
  return s;
}

function dynamicSections(results) {
  const d = results.dynamic;
  if (!d) return [];
  const out = [];
  out.push(section('dynamic', 'Dynamic transmission error',
    table([
      { label: 'Quantity', value: (r) => r[0] },
      { label: 'Value', value: (r) => r[1], class: 'n' },
    ], [
      ['Peak-to-peak ± U [arcsec]', uncertain(d, 'p2p_arcsec')],
      ['RMS ± U [arcsec]', uncertain(d, 'rms_arcsec')],
      ['Mean ± U [arcsec]', uncertain(d, 'mean_arcsec')],
      ['Input speed [rev/s]', num(d.input_speed_hz)],
      ['Sample rate [Hz]', num(d.sample_rate_hz)],
      ['Output revolutions', num(d.output_revolutions)],
      ['Samples analysed', d.samples],
      ['Missed cycles', d.missed_cycles],
    ], { id: 'dynamic-table' })));
  const ratio = results.gear ? results.gear.ratio : null;
  const outputHz = ratio ? d.input_speed_hz / ratio : null;
  const peaks = d.peaks || [];
  const aliased = d.aliased || [];
  const spec = d.order_spectrum || { order_output: [], amplitude_arcsec: [] };
  const specBox = plotBox('spectrum-plot', 'Order spectrum of TE (output orders), named peaks labelled; aliased orders marked where they fold to');
  out.push(section('spectrum', 'Order spectrum',
    specBox,
    table([
      { label: 'Peak', value: (p) => p.name },
      { label: 'Output order', value: (p) => num(p.order_output), class: 'n' },
      { label: 'Input order', value: (p) => (p.order_input == null ? '–' : num(p.order_input)), class: 'n' },
      { label: 'Frequency [Hz]', value: (p) => num(p.frequency_hz ?? p.folded_hz), class: 'n' },
      { label: 'Amplitude ± U [arcsec]', value: (p) => uncertain(p, 'amplitude_arcsec'), class: 'n' },
    ], [...peaks, ...aliased.map((a) => ({ name: `${a.name} (aliased from ${num(a.frequency_hz)} Hz)`, order_output: outputHz ? a.folded_hz / outputHz : null, folded_hz: a.folded_hz, amplitude_arcsec: a.amplitude_arcsec }))],
    { id: 'peaks-table' })));
  const amplitude = spec.amplitude_arcsec.map((a) => (a > 0 ? a : null));
  // Where an aliased order with no amplitude of its own is marked: on the curve.
  const spectrumAt = (order) => {
    let best = null;
    spec.order_output.forEach((o, i) => {
      if (amplitude[i] != null && (best == null || Math.abs(o - order) < Math.abs(spec.order_output[best] - order))) best = i;
    });
    return best == null ? null : amplitude[best];
  };
  // Named peaks only ('unnamed' ones are in the table), largest first, a few: labels that
  // overlap cannot be read.
  const named = (p) => p.name && !p.name.startsWith('unnamed');
  const shortName = (name) => name.replace(/\s*\(.*\)$/, '');
  const labels = [
    ...peaks.filter(named).slice(0, 8).map((p) => ({ x: p.order_output, y: p.amplitude_arcsec, text: shortName(p.name) })),
    ...(outputHz ? aliased.filter(named).map((a) => ({ x: a.folded_hz / outputHz, y: a.amplitude_arcsec > 0 ? a.amplitude_arcsec : spectrumAt(a.folded_hz / outputHz), text: `${shortName(a.name)} (aliased)`, color: '#a0314f' })) : []),
  ];
  out.draws = [() => makePlot(specBox.querySelector('.plot-area'), {
    xLabel: 'output order', yLabel: 'amplitude [arcsec]', logY: true,
    series: [{ label: 'TE amplitude' }],
    data: [spec.order_output, amplitude],
    labels: () => labels,
  })];
  return out;
}

function lostMotionFitSections(results) {
  const f = results.lost_motion_fit;
  if (!f) return [];
  const k = f.stiffness || {};
  const box = plotBox('torque-twist-plot', 'Torque against twist, with the fitted K1/K2/K3 per travel direction');
  const s = section('lost-motion-fit', 'Lost motion and stiffness',
    table([
      { label: 'Quantity', value: (r) => r[0] },
      { label: 'Value', value: (r) => r[1], class: 'n' },
    ], [
      [`Lost motion at ±${num(f.lost_motion_torque_nm, 3)} N·m [arcmin]`, uncertain(f, 'lost_motion_arcmin')],
      ['Backlash ± U [arcmin]', uncertain(f, 'backlash_arcmin')],
      ['Hysteresis loss [J]', num(f.hysteresis_loss_j)],
      ['K1 ± U [N·m/rad]', uncertain(k, 'k1_nm_per_rad')],
      ['K2 ± U [N·m/rad]', uncertain(k, 'k2_nm_per_rad')],
      ['K3 ± U [N·m/rad]', uncertain(k, 'k3_nm_per_rad')],
      ['T1 / T2 [N·m]', `${num(k.t1_nm)} / ${num(k.t2_nm)}`],
      ['Fit residual RMS [arcsec]', num(k.rms_residual_arcsec)],
      ['Rated torque [N·m]', num(f.rated_torque_nm)],
    ], { id: 'lost-motion-fit-table' }),
    box);
  const points = f.points || [];
  s.draws = [() => {
    const branches = [1, -1].map((travel) => points.filter((p) => p.travel === travel));
    const pairs = branches.map((b) => [b.map((p) => p.twist_arcmin), b.map((p) => p.torque_nm)]);
    const series = [
      { label: 'measured, forward', color: palette[0], points: true },
      { label: 'measured, reverse', color: palette[1], points: true },
    ];
    // The fitted model per travel branch as results.json carries it (computed once by the
    // procedure): drawn, not recomputed.
    for (const b of Array.isArray(f.fit_curve) ? f.fit_curve : []) {
      if (!Array.isArray(b.torque_nm) || !Array.isArray(b.twist_arcmin)) continue;
      const reverse = b.travel < 0;
      pairs.push([b.twist_arcmin, b.torque_nm]);
      series.push({ label: `fit K1/K2/K3, ${reverse ? 'reverse' : 'forward'}`, color: palette[reverse ? 3 : 2], width: 2, spanGaps: true });
    }
    makePlot(box.querySelector('.plot-area'), {
      xLabel: 'twist [arcmin]', yLabel: 'torque [N·m]', series, data: joinSeries(pairs),
    });
  }];
  return [s];
}

// The locked-output torsional test: its figures with their uncertainty and budget, and the loop
// as the catalogues draw it (torque on x, torsion angle on y).
function torsionalSections(results) {
  const t = results.torsional;
  if (!t) return [];
  const k = t.stiffness || {};
  const figures = [
    ['Hysteresis loss [arcmin]', t.hysteresis_loss_arcmin],
    [`Lost motion at ±${num(t.lost_motion_torque_nm, 3)} N·m [arcmin]`, t.lost_motion_arcmin],
    ['Backlash [arcmin]', t.backlash_arcmin],
    ['K1 [N·m/rad]', k.k1_nm_per_rad],
    ['K2 [N·m/rad]', k.k2_nm_per_rad],
    ['K3 [N·m/rad]', k.k3_nm_per_rad],
    ['T1 [N·m]', k.t1_nm],
    ['T2 [N·m]', k.t2_nm],
  ];
  const box = plotBox('torsional-plot', 'Twist against torque, output locked: first loading, unloading, reloading, and the fitted K1/K2/K3');
  const facts = [
    ['T_max [N·m]', `${num(t.t_max_nm)} (${t.t_max_reason || '–'})`],
    ['Hold torque [N·m]', num(t.hold_torque_nm)],
    ['Points used / voided (slip)', `${t.points_used ?? '–'} / ${t.points_voided ?? '–'}`],
    ['Largest output motion [arcmin]', num(t.slip && t.slip.max_output_moved_arcmin)],
    ['Fit residual RMS [arcsec]', num(k.rms_residual_arcsec)],
  ];
  const budget = [];
  for (const [label, f] of figures) {
    for (const c of (f && f.budget) || []) budget.push({ figure: label, ...c });
  }
  const s = section('torsional', 'Torsional stiffness (locked output)',
    table([
      { label: 'Figure', value: (r) => r[0] },
      { label: 'Value ± U (k = 2)', value: (r) => figureText(r[1]), class: 'n' },
    ], figures, { id: 'torsional-table' }),
    box,
    table([
      { label: 'Quantity', value: (r) => r[0] },
      { label: 'Value', value: (r) => r[1], class: 'n' },
    ], facts, { id: 'torsional-facts' }),
    el('details', {}, el('summary', {}, 'Uncertainty budget'),
      table([
        { label: 'Figure', value: (r) => r.figure },
        { label: 'Contribution', value: (r) => r.source },
        { label: 'Type', value: (r) => r.type },
        { label: 'Standard uncertainty', value: (r) => num(r.standard, 3), class: 'n' },
      ], budget, { id: 'torsional-budget' })));
  const points = t.points || [];
  s.draws = [() => {
    const pairs = [];
    const series = [];
    [['first_loading', 'first loading'], ['unloading', 'unloading'], ['reloading', 'reloading']].forEach(([key, label], i) => {
      const b = points.filter((p) => p.branch === key && !p.voided);
      if (!b.length) return;
      pairs.push([b.map((p) => p.torque_nm), b.map((p) => p.twist_arcmin)]);
      series.push({ label, color: palette[i], points: true, line: true, spanGaps: true });
    });
    const voided = points.filter((p) => p.voided);
    if (voided.length) {
      pairs.push([voided.map((p) => p.torque_nm), voided.map((p) => p.twist_arcmin)]);
      series.push({ label: 'voided (slip)', color: palette[6], points: true });
    }
    // The fitted curve as results.json carries it (each side of zero at its own offset,
    // computed once by the procedure): drawn, not recomputed.
    for (const side of Array.isArray(t.fit_curve) ? t.fit_curve : []) {
      if (!Array.isArray(side.torque_nm) || !Array.isArray(side.twist_arcmin)) continue;
      pairs.push([side.torque_nm, side.twist_arcmin]);
      series.push({ label: side.side === 'negative' ? 'fit K1/K2/K3, T < 0' : 'fit K1/K2/K3, T > 0', color: palette[3], width: 2, spanGaps: true });
    }
    makePlot(box.querySelector('.plot-area'), {
      xLabel: 'torque [N·m]', yLabel: 'twist θ_in/N − θ_out [arcmin]', series, data: joinSeries(pairs), height: 360,
    });
  }];
  return [s];
}

function twinSections(run, results) {
  const t = results.twin;
  if (!t) return [];
  if (t.error && !t.samples_received) {
    return [section('twin', 'Gear twin', el('p', { class: 'warning' }, `The twin did not run: ${t.error}`))];
  }
  const cal = t.calibration;
  // Which twin ran: the unit's own (calibrated over its earlier runs) or the bench's nominal one.
  const gear = t.gear;
  const twinUsed = !gear ? '–'
    : gear.kind === 'unit'
      ? `unit twin (${gear.case}), calibrated over ${(gear.calibrated_from || []).map((r) => `${r.procedure} ${r.run_id}`).join(', ')}`
      : `nominal twin case (${gear.case})`;
  const rows = [
    ['Twin beside the bench', twinUsed],
    ['Residual RMS, live twin [arcsec]', num(t.residual && t.residual.rms_arcsec)],
    ['Residual p2p, live twin [arcsec]', num(t.residual && t.residual.p2p_arcsec)],
  ];
  if (t.residual && t.residual.rms_over_noise_floor != null) {
    rows.push(['Live residual RMS / noise floor', num(t.residual.rms_over_noise_floor)]);
  }
  if (cal) {
    rows.push(['Residual RMS before calibration [arcsec]', num(cal.rms_before_arcsec)],
      ['Residual RMS after calibration [arcsec]', num(cal.rms_after_arcsec)],
      ['Noise floor [arcsec]', num(cal.noise_floor_arcsec)],
      ['Backlash nominal → calibrated [arcmin]', `${num(cal.backlash_nominal_arcmin)} → ${num(cal.backlash_calibrated_arcmin)}`],
      ['Stiffness factor', num(cal.stiffness_factor)],
      ['Fitted', (cal.fitted || []).join(', ') || '–']);
  }
  const unit = t.unit_twin;
  if (unit && unit.error) {
    rows.push(['Unit twin not updated', unit.error]);
  } else if (unit) {
    const k = unit.stiffness || {};
    rows.push(['Unit twin updated from', (unit.runs || []).map((r) => `${r.procedure} (${num(r.rms_after_over_noise_floor)} × floor)`).join(', ')]);
    if (k.form === 'three_segment') {
      rows.push(['Unit twin K1 / K2 / K3 [N·m/rad]', `${num(k.k1_nm_per_rad)} / ${num(k.k2_nm_per_rad)} / ${num(k.k3_nm_per_rad)}`],
        ['Unit twin T1 / T2 [N·m]', `${num(k.t1_nm)} / ${num(k.t2_nm)}`]);
    }
    rows.push(['Unit twin backlash [arcmin]', num(unit.backlash_arcmin)]);
  }
  rows.push(['Samples predicted / dropped', `${t.samples_predicted ?? '–'} / ${t.samples_dropped ?? '–'}`]);
  if (t.error) rows.push(['Stopped early', t.error]);
  const teBox = plotBox('twin-plot', "Measured TE and the twin's prediction, before and after calibration");
  const resBox = plotBox('twin-residual-plot', 'Residual (measured − twin)');
  const s = section('twin', 'Gear twin',
    table([{ label: 'Quantity', value: (r) => r[0] }, { label: 'Value', value: (r) => r[1], class: 'n' }], rows, { id: 'twin-table' }),
    teBox, resBox);
  s.draws = [async () => {
    const columns = Math.min(4000, plotWidth(teBox.querySelector('.plot-area')));
    const tw = await readRun(`/api/runs/${encodeURIComponent(run.id)}/twin?columns=${columns}`);
    const before = tw.before && !tw.before.error ? tw.before : null;
    const after = tw.after && !tw.after.error ? tw.after : null;
    if (!before && !after) {
      teBox.querySelector('.plot-area').append(el('p', { class: 'note' }, 'This run folder holds no twin curves (twin.csv).'));
      resBox.remove();
      return;
    }
    // The measured TE goes last, drawn over the predictions (after calibration they overlap).
    const te = [];
    const teSeries = [];
    const res = [];
    const resSeries = [];
    if (before) {
      te.push([before.t_s, before.series.predicted_te_arcsec]);
      teSeries.push({ label: 'twin, before calibration', color: palette[1] });
      res.push([before.t_s, before.series.residual_arcsec]);
      resSeries.push({ label: 'residual, before calibration', color: palette[1] });
    }
    if (after) {
      te.push([after.t_s, after.series.predicted_te_arcsec]);
      teSeries.push({ label: 'twin, after calibration', color: palette[2] });
      res.push([after.t_s, after.series.residual_arcsec]);
      resSeries.push({ label: 'residual, after calibration', color: palette[2] });
    }
    const measured = before || after;
    te.push([measured.t_s, measured.series.measured_te_arcsec]);
    teSeries.push({ label: 'measured', color: '#222', width: 1 });
    makePlot(teBox.querySelector('.plot-area'), { xLabel: 'bench time [s]', yLabel: 'TE [arcsec]', series: teSeries.map((x) => ({ ...x, spanGaps: te.length > 1 })), data: joinSeries(te) });
    makePlot(resBox.querySelector('.plot-area'), { xLabel: 'bench time [s]', yLabel: 'residual [arcsec]', series: resSeries.map((x) => ({ ...x, spanGaps: res.length > 1 })), data: joinSeries(res) });
  }];
  return [s];
}

function exportsSection(run, detail) {
  const base = `/api/runs/${encodeURIComponent(run.id)}`;
  return section('exports', 'Exports',
    el('ul', { class: 'exports' },
      el('li', {}, el('a', { href: base }, 'run record and results (JSON)')),
      el('li', {}, el('a', { href: `${base}/samples?from=0&limit=1000` }, 'samples, first page (JSON)')),
      el('li', {}, el('a', { href: `${base}/trace?channels=te_arcsec,torque,input_speed&columns=2000` }, 'TE, torque and speed trace (JSON)')),
      detail.report ? el('li', {}, `static report on the bench computer: ${detail.report}`) : null,
      el('li', {}, `run folder: ${detail.dir || '–'}`)));
}

function showError(e) {
  message.hidden = false;
  message.className = 'message error';
  message.textContent = e.message || String(e);
}

async function main_() {
  if (!id) throw new Error('No run given: open this page as /run?id=<run id> (from the history).');
  const detail = await readRun(`/api/runs/${encodeURIComponent(id)}`);
  const run = detail.run;
  const results = detail.results || {};
  document.title = `${run.unit_serial || ''} ${run.procedure} ${run.id} – wavebench`;
  message.hidden = true;
  const sections = [header(run, results)];
  const limits = limitChecks(results);
  if (limits) sections.push(limits);
  // Every figure the procedure declares (src/figures), as GET /api/procedures serves them.
  const figures = declaredFiguresSection(await declaredFiguresOf(get, run.procedure), results);
  if (figures) sections.push(figures);
  if (results.warnings && results.warnings.length) {
    sections.push(el('div', { class: 'warning' }, results.warnings.map((w) => el('p', {}, w))));
  }
  const draws = [];
  const add = (group) => {
    const list = Array.isArray(group) ? group : [group];
    sections.push(...list);
    draws.push(...(list.draws || []));
    for (const one of list) draws.push(...(one.draws || []));
  };
  add(staticSections(results));
  add(dynamicSections(results));
  add(lostMotionFitSections(results));
  add(torsionalSections(results));
  if (detail.samples_file_bytes > 0) {
    add(traceSection(run, run.procedure === 'dynamic'
      ? 'Dynamic TE against time (the whole record; zoom in for every sample)'
      : 'The record against time (zoom in for every sample)', 'te_arcsec'));
  }
  add(twinSections(run, results));
  add(twinDiagnosisSection(results));
  add(exportsSection(run, detail));
  main.append(...sections);
  if (run.status === 'running') {
    // Recording, or recorded with its results still being made: they arrive when done.
    awaitResults(detail, message, () => readRun(`/api/runs/${encodeURIComponent(id)}`),
      () => window.location.reload());
  }
  // Plots are drawn once their boxes are laid out (they take the box's width).
  for (const draw of draws) {
    try {
      await draw();
    } catch (e) {
      showError(e);
    }
  }
  document.body.dataset.ready = 'true';
}

main_().catch(showError);
