// The operator console: start form, progress and verdict, live plots, bench panel, stop. The
// daemon's status arrives with the live stream (every fifth frame), so nothing here polls but
// the session check, which also keeps the session alive while the page is open.
import { get, post } from './api.js';
import { LivePlots } from './live_plots.js';
import { StartForm } from './start_form.js';
import { diagnosisFlagsTable } from './twin_diagnosis.js';
import { uncertain } from './figures.js';
import { SettledPointsPlot } from './settled_points_plot.js';
import { showPostRuns, timeLeft } from './run_progress.js';

const $ = (id) => document.getElementById(id);
let loggedIn = false;
let lastStatus = null;
let shownRun = null;
let runId = null;       // the active run's id, once the daemon has named it
let runActive = false;  // a run was active at the last status
let shownFlags = '';
// The unit mounted, for the header: the active run's serial, else the one entered for the
// next run, else the last run's.
const unit = { run: null, entered: '', last: null };

function message(text, error = false) {
  $('message').textContent = text;
  $('message').className = error ? 'error' : '';
}

function fmt(v, digits = 3) {
  if (v === null || v === undefined) return '—';
  if (typeof v === 'number') return Number.isInteger(v) ? String(v) : v.toPrecision(digits);
  if (typeof v === 'boolean') return v ? 'yes' : 'no';
  if (Array.isArray(v)) return v.map((x) => fmt(x, digits)).join(', ');
  return String(v);
}

function table(el, rows) {
  el.replaceChildren(...rows.map(([k, v]) => {
    const tr = document.createElement('tr');
    const th = document.createElement('th');
    th.textContent = k;
    const td = document.createElement('td');
    td.textContent = v;
    tr.append(th, td);
    return tr;
  }));
}

function setSession(authenticated) {
  loggedIn = authenticated;
  document.body.classList.toggle('read-only', !authenticated);
  $('reset').disabled = !authenticated;
  form.setEnabled(authenticated && lastStatus !== null && lastStatus.state === 'ready');
}

async function checkSession() {
  try {
    setSession((await get('/api/session')).authenticated);
  } catch (_) {
    setSession(false);
  }
}

function showUnit() {
  const serial = unit.run || unit.entered || unit.last;
  $('unit-mounted').textContent = serial ? `unit ${serial}` : 'no unit serial entered';
}

function showBench(s) {
  $('lifecycle').textContent = `${s.state} · ${s.lifecycle}`;
  $('lifecycle').className = `badge ${s.lifecycle}`;
  $('bench-name').textContent = s.bench ? s.bench.name : (s.connect_error || '');
  showUnit();
  const a = s.acquisition || {};
  const rows = [
    ['drive (CiA 402)', fmt(a.drive_state)],
    ['drive statusword', a.drive_statusword === null || a.drive_statusword === undefined ? '—'
      : `0x${a.drive_statusword.toString(16).padStart(4, '0')}`],
    ['brake output', fmt(a.brake_output_on)],
    ['brake coil temperature', a.brake_coil_temperature_c === null || a.brake_coil_temperature_c === undefined
      ? '—' : `${a.brake_coil_temperature_c.toFixed(1)} °C`],
    ['brake status / alarm', `${a.brake_status_word === null || a.brake_status_word === undefined ? '—'
      : `0x${a.brake_status_word.toString(16).padStart(4, '0')}`} / ${a.brake_alarm || 'no alarm'}`],
    ['SYNC rate', a.real_time_s > 0 ? `${fmt(a.syncs_sent / a.real_time_s, 4)} /s` : '—'],
    ['SYNC lateness p50 / p99 / max', [a.sync_lateness_p50_s, a.sync_lateness_p99_s, a.sync_lateness_max_s]
      .map((x) => (x === undefined || x === null ? '—' : `${(x * 1e6).toFixed(0)} µs`)).join(' / ')],
    ['SYNC late / skipped', `${fmt(a.sync_late)} / ${fmt(a.sync_skipped)}`],
    ['missed cycles (timed out)', fmt(a.cycles_timed_out)],
    ['cycles waited for slow devices (longest)', a.cycles_waited_for_devices ? `${a.cycles_waited_for_devices} (${(1e3 * a.longest_device_wait_s).toFixed(0)} ms)` : fmt(a.cycles_waited_for_devices)],
    ['incomplete samples', fmt(a.incomplete_samples)],
    ['bus load', a.bus_load === undefined ? '—' : `${(100 * a.bus_load).toFixed(1)} %`],
    ['samples', fmt(a.samples)],
    ['bench time', a.bench_time_s === undefined ? '—' : `${a.bench_time_s.toFixed(1)} s`],
  ];
  rows.push(['drive heartbeats (max gap)', a.drive_heartbeats === undefined ? '—'
    : `${a.drive_heartbeats} (${fmt(a.drive_heartbeat_gap_max_s, 2)} s)`]);
  const l = s.latest || {};
  const rpm = l.input_speed_rad_s === null || l.input_speed_rad_s === undefined ? null
    : l.input_speed_rad_s * 60 / (2 * Math.PI);
  const deg = l.theta_out_rad === null || l.theta_out_rad === undefined ? null
    : (((l.theta_out_rad * 180) / Math.PI) % 360 + 360) % 360;  // the unwrapped angle, within a turn
  rows.unshift(
    ['input speed', rpm === null ? '—' : `${rpm.toFixed(1)} rpm`],
    ['output angle', deg === null ? '—' : `${deg.toFixed(3)} °`],
    ['torque', l.torque_nm === null || l.torque_nm === undefined ? '—' : `${l.torque_nm.toFixed(2)} N·m`],
    ['brake current / torque', `${fmt(l.brake_current_a)} A / ${fmt(l.brake_torque_nm)} N·m`],
  );
  table($('acquisition'), rows);
  // NMT state and heartbeat (or node-guarding answer) age per node, from the bench's watches.
  const nodes = new Map((a.nodes || []).map((n) => [n.node, n]));
  table($('devices'), (s.devices || []).map((d) => {
    const n = nodes.get(d.node) || {};
    const drive = d.node !== null && d.node !== undefined && a.drive_state && (d.commands || []).length
      ? a.drive_state : null;
    const age = n.heartbeat_age_s === null || n.heartbeat_age_s === undefined ? null
      : `${n.supervision === 'node guarding' ? 'guard answer' : 'heartbeat'} ${fmt(n.heartbeat_age_s, 2)} s ago`;
    const state = [n.nmt_state, drive, age]
      .filter((x) => x).join(' · ');
    return [`${d.name}${d.node !== null && d.node !== undefined ? ` (node ${d.node})` : ''}`,
      state || (d.channels || []).map((c) => c.name).join(', ')];
  }));
}

function showRun(s) {
  const run = s.run;
  if (run && (!runActive || (runId !== null && run.id !== null && run.id !== runId))) newRun(run);
  else if (run && runId === null && run.id !== null) runNamed(run.id);
  if (!run && runActive) {
    runActive = false;
    unit.last = unit.run || unit.last;
    unit.run = null;
  }
  showProgress(run);
  if ($('post-runs')) showPostRuns($('post-runs'), s.post_runs);
  if (run) xyPlot.show(run);
  const last = s.last_run;
  // Shown anew when its state moves on (processing, then complete: the verdict arrives
  // with the results).
  if (!run && last && last.id && runKey(last) !== shownRun) {
    shownRun = runKey(last);
    showLastRun(last);
  }
}

// A run began (this page's or another client's): the last verdict and the last run's points
// go at once.
function newRun(run) {
  runActive = true;
  runId = null;
  clearVerdict();
  xyPlot.clear();
  if (run.id !== null) runNamed(run.id);
}

// The header names the unit under test, as the run records it.
function runNamed(id) {
  runId = id;
  get(`/api/runs/${encodeURIComponent(id)}`).then((d) => {
    if (runId === id && runActive && d.run && d.run.unit_serial) {
      unit.run = d.run.unit_serial;
      showUnit();
    }
  }).catch(() => {});
}

// A finished run as shown: its id and its state (processing, then complete).
function runKey(last) {
  return `${last.id} ${last.status}`;
}

function clearVerdict() {
  $('last-run').hidden = true;
  $('verdict').textContent = '';
  $('verdict').className = 'verdict';
  $('verdict-of').textContent = '';
  $('static-table').hidden = true;
  if (lastStatus && lastStatus.last_run) shownRun = runKey(lastStatus.last_run);
}

// Progress of the active run: procedure, phase, fraction and an estimate of the time left.
function showProgress(run) {
  $('progress').hidden = !run;
  if (!run) return;
  $('run-procedure').textContent = `${run.procedure} ${run.id || ''}`;
  $('run-phase').textContent = run.phase || '…';
  const f = run.progress || 0;
  $('run-percent').textContent = `${(100 * f).toFixed(0)} %`;
  $('run-bar').value = f;
  $('run-left').textContent = timeLeft(run.remaining_s);
  showDiagnosis(run.diagnosis_flags || []);
}

// The twin's flags while the run goes on (redrawn only when they change).
function showDiagnosis(flags) {
  const key = JSON.stringify(flags.map((f) => [f.order, f.revolutions]));
  if (key === shownFlags) return;
  shownFlags = key;
  const box = $('run-diagnosis');
  box.hidden = !flags.length;
  box.replaceChildren(box.firstElementChild, ...(flags.length ? [diagnosisFlagsTable(flags, 'run-diagnosis-table')] : []));
}

// "2026-11-27 15:04:05" in the browser's local time; the daemon's times are UTC ISO 8601
// (with microseconds, which Date does not need).
function localTime(iso) {
  if (!iso) return '';
  const d = new Date(String(iso).replace(/(\.\d{3})\d+/, '$1'));
  if (Number.isNaN(d.getTime())) return String(iso);
  const two = (n) => String(n).padStart(2, '0');
  return `${d.getFullYear()}-${two(d.getMonth() + 1)}-${two(d.getDate())} ` +
    `${two(d.getHours())}:${two(d.getMinutes())}:${two(d.getSeconds())}`;
}

function procedureTitle(name) {
  const p = form.procedures.find((x) => x.name === name);
  return p ? p.title || name : name;
}

async function showLastRun(last) {
  $('last-run').hidden = false;
  $('last-run-link').textContent = last.id;
  $('last-run-link').href = `/run?id=${encodeURIComponent(last.id)}`;
  $('last-run-status').textContent = last.status;
  $('last-run-status').className = `status ${last.status}`;
  $('last-run-reason').textContent = last.reason ? `(${last.reason})` : '';
  const verdict = $('verdict');
  verdict.textContent = '';
  verdict.className = 'verdict';
  $('verdict-of').textContent = '';
  $('static-table').hidden = true;
  try {
    const detail = await get(`/api/runs/${encodeURIComponent(last.id)}`);
    if (runActive || shownRun !== runKey(last)) return;  // a newer run began meanwhile
    const results = detail.results || {};
    const run = detail.run || {};
    if (results.verdict === 'PASS' || results.verdict === 'FAIL' || results.verdict === 'UNDECIDED') {
      // UNDECIDED: a limit inside a figure's uncertainty interval (ISO 14253-1), shown as such.
      verdict.textContent = results.verdict;
      verdict.className = `verdict ${results.verdict.toLowerCase()}`;
      verdict.title = results.verdict === 'UNDECIDED'
        ? `a limit lies inside a figure's uncertainty interval; counts as ${results.undecided_counts_as || 'fail'} for acceptance`
        : '';
    } else if (last.status === 'processing') {
      // Recorded; the verdict comes with the results (post-run work in the background).
      verdict.textContent = 'verdict pending: results being made';
      verdict.className = 'verdict none';
      verdict.title = 'the bench is free for the next unit; the verdict appears here when ready';
    } else if (last.status !== 'complete') {
      verdict.textContent = last.status.toUpperCase();
      verdict.className = 'verdict aborted';
    } else {
      verdict.textContent = 'no verdict';
      verdict.className = 'verdict none';
      verdict.title = 'the run had no spec to judge it against';
    }
    // Which unit, which procedure, when: the verdict is never read for the wrong unit.
    $('verdict-of').textContent = [
      run.unit_serial ? `unit ${run.unit_serial}` : 'no unit serial',
      procedureTitle(run.procedure || ''),
      run.spec ? `spec ${run.spec}` : null,
      localTime(run.finished_at || run.started_at),
    ].filter((x) => x).join(' · ');
    if (run.unit_serial) {
      unit.last = run.unit_serial;
      showUnit();
    }
    if (Array.isArray(results.static) && results.static.length) staticTable(results.static);
  } catch (_) {
    // the run page has the details
  }
}

// The static table's columns as the operator reads them (results.json keys otherwise).
const STATIC_COLUMNS = {
  direction: 'direction',
  load_nm: 'load [N·m]',
  mean_arcmin: 'mean TE [arcmin]',
  p2p_arcmin: 'TE peak–peak [arcmin]',
  std_arcmin: 'TE std. dev. [arcmin]',
};

function staticTable(entries) {
  const keys = Object.keys(entries[0]).filter((k) => entries.every((e) => typeof e[k] !== 'object' || e[k] === null));
  const t = $('static-table');
  const head = document.createElement('tr');
  for (const k of keys) {
    const th = document.createElement('th');
    th.textContent = STATIC_COLUMNS[k] || k;
    head.append(th);
  }
  const rows = entries.map((e) => {
    const tr = document.createElement('tr');
    for (const k of keys) {
      const td = document.createElement('td');
      // A figure with an uncertainty beside it: value ± U (k = 2) to the digits U supports,
      // its budget on hover/click.
      if (e.uncertainty && e.uncertainty[k]) td.append(uncertain(e, k));
      else td.textContent = fmt(e[k], 4);
      tr.append(td);
    }
    return tr;
  });
  t.replaceChildren(head, ...rows);
  t.hidden = false;
}

function showStatus(s) {
  lastStatus = s;
  showBench(s);
  showRun(s);
  $('fault').hidden = !s.fault_reason;
  $('fault-reason').textContent = s.fault_reason || '';
  form.setEnabled(loggedIn && s.state === 'ready');
}

// The stop (button and Esc) is the stop bar's, on every page (stop_bar.js).

async function reset() {
  try {
    showStatus(await post('/api/reset'));
    message('Bench reset.');
  } catch (e) {
    message(`Reset failed: ${e.message}`, true);
  }
}

const form = new StartForm({
  onStarted: (answer, request) => {
    message(`Run ${answer.run_id || ''} started.`);
    clearVerdict();
    unit.run = request.unit_serial || null;
    showUnit();
  },
  onSerial: (serial) => {
    unit.entered = serial;
    showUnit();
  },
});
const xyPlot = new SettledPointsPlot();
window.wavebenchXY = xyPlot;
const plots = new LivePlots({ onStatus: showStatus });
window.wavebenchLive = plots;

$('reset').addEventListener('click', reset);
$('window').addEventListener('change', () => plots.connect(Number($('window').value)));

get('/api/status').then(showStatus).catch((e) => message(e.message, true));
checkSession();
setInterval(checkSession, 60000);
form.load();
plots.connect(Number($('window').value));
