// The operator console: bench panel, live plots, start form, stop, progress and verdict. The
// daemon's status arrives with the live stream (every fifth frame), so nothing here polls but
// the session check, which also keeps the session alive while the page is open.
import { api, get, post } from './api.js';
import { LivePlots } from './live_plots.js';
import { StartForm } from './start_form.js';
import { diagnosisFlagsTable } from './twin_diagnosis.js';
import { uncertain } from './dom.js';

const $ = (id) => document.getElementById(id);
let loggedIn = false;
let lastStatus = null;
let shownRun = null;
let runStartedAt = null;
let runId = null;
let shownFlags = '';

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
  $('login-link').hidden = authenticated;
  $('logout').hidden = !authenticated;
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

function showBench(s) {
  $('lifecycle').textContent = `${s.state} · ${s.lifecycle}`;
  $('lifecycle').className = `badge ${s.lifecycle}`;
  $('bench-name').textContent = s.bench ? `${s.bench.name} · ${s.bench.unit_serial || ''}` : (s.connect_error || '');
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
  $('progress').hidden = !run;
  if (run) {
    if (runId !== run.id) {
      runId = run.id;
      runStartedAt = Date.now();
    }
    $('run-procedure').textContent = `${run.procedure} ${run.id || ''}`;
    $('run-phase').textContent = run.phase || '…';
    const f = run.progress || 0;
    $('run-percent').textContent = `${(100 * f).toFixed(0)} %`;
    $('run-bar').value = f;
    const elapsed = (Date.now() - runStartedAt) / 1000;
    $('run-left').textContent = f > 0.02 && f < 1 ? `${Math.round(elapsed * (1 - f) / f)} s left` : '';
    showDiagnosis(run.diagnosis_flags || []);
  }
  const last = s.last_run;
  if (last && last.id && last.id !== shownRun) {
    shownRun = last.id;
    showLastRun(last);
  }
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
  $('static-table').hidden = true;
  try {
    const detail = await get(`/api/runs/${encodeURIComponent(last.id)}`);
    const results = detail.results || {};
    if (results.verdict === 'PASS' || results.verdict === 'FAIL' || results.verdict === 'UNDECIDED') {
      // UNDECIDED: a limit inside a figure's uncertainty interval (ISO 14253-1), shown as such.
      verdict.textContent = results.verdict;
      verdict.className = `verdict ${results.verdict.toLowerCase()}`;
      verdict.title = results.verdict === 'UNDECIDED'
        ? `a limit lies inside a figure's uncertainty interval; counts as ${results.undecided_counts_as || 'fail'} for acceptance`
        : '';
    } else if (last.status !== 'complete') {
      verdict.textContent = last.status.toUpperCase();
      verdict.className = 'verdict aborted';
    }
    if (Array.isArray(results.static) && results.static.length) staticTable(results.static);
  } catch (_) {
    // the run page has the details
  }
}

function staticTable(entries) {
  const keys = Object.keys(entries[0]).filter((k) => entries.every((e) => typeof e[k] !== 'object' || e[k] === null));
  const t = $('static-table');
  const head = document.createElement('tr');
  for (const k of keys) {
    const th = document.createElement('th');
    th.textContent = k;
    head.append(th);
  }
  const rows = entries.map((e) => {
    const tr = document.createElement('tr');
    for (const k of keys) {
      const td = document.createElement('td');
      // A figure with an uncertainty beside it: value ± U (k = 2), its budget on hover/click.
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
  onStarted: (answer) => message(`Run ${answer.run_id || ''} started.`),
});
const plots = new LivePlots({ onStatus: showStatus });
window.wavebenchLive = plots;

$('reset').addEventListener('click', reset);
$('logout').addEventListener('click', async () => {
  try {
    await api('DELETE', '/api/session');
  } catch (_) {
    // logged out either way
  }
  setSession(false);
});
$('window').addEventListener('change', () => plots.connect(Number($('window').value)));

get('/api/status').then(showStatus).catch((e) => message(e.message, true));
checkSession();
setInterval(checkSession, 60000);
form.load();
plots.connect(Number($('window').value));
