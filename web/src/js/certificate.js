// The test certificate of one run (/certificate?id=...): one A4 page a customer can file, read
// from GET /api/runs/{id}. A certificate states a verdict, so only a complete run judged
// against a spec gets one; any other run prints as "NOT A CERTIFICATE" with the reason.
// Figure names and units come from results.json's limit_checks (the verdict table's
// declaration), figures are written to the digits their uncertainty supports (figures.js).
import { el, num, table, verdictOf } from './dom.js';
import { plusMinus, utcSeconds, limitName, whereText } from './figures.js';
import { readRun } from './run_reads.js';

const id = new URLSearchParams(location.search).get('id') || '';
const main = document.getElementById('certificate');
const message = document.getElementById('message');
document.getElementById('print').addEventListener('click', () => window.print());
document.getElementById('run-link').href = `/run?id=${encodeURIComponent(id)}`;

// Why this run gets no certificate (null: it gets one).
export function notCertificateReason(run, results) {
  if (run.status === 'running') return 'run still running';
  if (run.status === 'aborted') return `run aborted: ${run.reason || results.abort_reason || 'no reason recorded'}`;
  if (run.status === 'incomplete') return `run incomplete: ${run.reason || 'the daemon stopped during it'}`;
  if (run.status !== 'complete') return `run ${run.status}`;
  if (!verdictOf(run, results)) return 'the run was made without a spec, so it has no verdict';
  if (!Array.isArray(results.limit_checks) || !results.limit_checks.length) return 'no limit of the spec applies to this run';
  return null;
}

const fact = (label, value, cls) => [el('dt', {}, label), el('dd', { class: cls }, value ?? '–')];

function duration(run) {
  const a = Date.parse(run.started_at);
  const b = Date.parse(run.finished_at);
  if (!Number.isFinite(a) || !Number.isFinite(b) || b < a) return null;
  const s = Math.round((b - a) / 1000);
  return s < 60 ? `${s} s` : `${Math.floor(s / 60)} min ${s % 60} s`;
}

function decisionCell(c) {
  const d = c.decision || (c.pass === true ? 'PASS' : c.pass === false ? 'FAIL' : '–');
  return el('span', { class: `decision-${d.toLowerCase()}` }, d);
}

function limitsTable(checks) {
  return table([
    { label: 'Figure [unit]', value: (c) => limitName(c) },
    { label: 'Measured at', value: whereText },
    { label: 'Limit', value: (c) => `${c.minimum ? '≥' : '≤'} ${num(c.value)}`, class: 'n' },
    { label: 'Measured ± U (k = 2)', value: (c) => (c.uncertainty_stated === false ? `${plusMinus(c.measured, null)} (no U stated)` : plusMinus(c.measured, c.expanded)), class: 'n' },
    { label: 'Decision', value: decisionCell },
  ], checks, { id: 'cert-limits' });
}

function sensorsTable(results, runDay) {
  const sensors = Array.isArray(results.bench_sensors) ? results.bench_sensors : [];
  if (!sensors.length) return el('p', { class: 'note' }, 'This run records no list of the bench\'s sensors.');
  return table([
    { label: 'Measuring device', value: (s) => s.sensor },
    { label: 'Calibration certificate', value: (s) => s.calibration_id || 'not stated in the bench config' },
    { label: 'Calibration due', value: (s) => {
      if (!s.calibration_due) return '–';
      const overdue = runDay && s.calibration_due < runDay;
      return el('span', { class: overdue ? 'overdue' : null }, overdue ? `${s.calibration_due} (overdue at test)` : s.calibration_due);
    } },
  ], sensors, { id: 'cert-sensors' });
}

function unitFacts(run, results) {
  const spec = results.spec || {};
  return el('dl', { class: 'cert-facts', id: 'cert-unit' },
    fact('Unit serial', run.unit_serial || results.unit_serial),
    fact('Gear model', spec.model),
    fact('Spec', spec.name ? `${spec.name}${spec.description ? ` – ${spec.description.replace(/N\*m/g, 'N·m')}` : ''}` : null),
    fact('Gear ratio', results.gear ? `${num(results.gear.ratio)} : 1` : null));
}

function testFacts(run, results) {
  return el('dl', { class: 'cert-facts', id: 'cert-test' },
    fact('Test', `${results.procedure || run.procedure} transmission test`),
    fact('Operator', results.operator ?? run.operator ?? 'not recorded'),
    fact('Started', utcSeconds(run.started_at)),
    fact('Finished', run.finished_at ? utcSeconds(run.finished_at) : null),
    fact('Duration', duration(run)),
    fact('Bench', results.bench),
    fact('Software', `wavebench ${results.software_version || run.software_version || '–'}${results.software_commit ? ` (${String(results.software_commit).slice(0, 12)})` : ''}`),
    fact('Config hash', run.config_hash ? run.config_hash.slice(0, 16) : null, 'mono'));
}

function head(run, verdict, undecidedAs) {
  return el('header', { class: 'cert-head' },
    el('div', {},
      el('h1', {}, 'Test certificate'),
      el('div', { class: 'issuer' }, 'Strain-wave gear transmission test · wavebench test bench')),
    verdict ? el('div', { class: `cert-verdict ${verdict.toLowerCase()}`, id: 'cert-verdict' }, verdict,
      verdict === 'UNDECIDED' ? el('small', {}, `counts as ${undecidedAs || 'fail'}`) : null) : null,
    el('div', { class: 'cert-number' }, 'Certificate no.', el('br'), el('strong', { class: 'mono' }, run.id)));
}

function approval(results, run) {
  const operator = results.operator ?? run.operator;
  return el('section', { class: 'approval', id: 'cert-approval' },
    el('div', { class: 'field' }, el('span', { class: 'written' }, operator || '\u00a0'), el('strong', {}, 'Tested by'), ' (name, signature)'),
    el('div', { class: 'field' }, el('span', { class: 'written' }, '\u00a0'), el('strong', {}, 'Approved by'), ' (name, signature)'),
    el('div', { class: 'field' }, el('span', { class: 'written' }, '\u00a0'), el('strong', {}, 'Date of approval')),
    el('div', { class: 'field' }, el('span', { class: 'written' }, '\u00a0'), el('strong', {}, 'Stamp')));
}

function certificate(run, results) {
  const verdict = verdictOf(run, results);
  const checks = results.limit_checks;
  const runDay = (run.started_at || '').slice(0, 10);
  return el('article', { class: 'sheet', id: 'sheet', 'data-certificate': 'true' },
    head(run, verdict, results.spec && results.spec.undecided),
    el('h2', {}, 'Unit under test'),
    unitFacts(run, results),
    el('h2', {}, 'Test'),
    testFacts(run, results),
    el('h2', {}, 'Results against the spec\'s limits'),
    limitsTable(checks),
    el('p', { class: 'cert-rule' },
      'U is the expanded uncertainty at k = 2 (about 95 % coverage, GUM). Decision rule ISO 14253-1: ',
      'PASS when the measured value ± U lies wholly within the limit, FAIL when wholly beyond it, ',
      `UNDECIDED when the limit lies inside the interval (counted as ${(results.spec && results.spec.undecided) || 'fail'} for acceptance).`),
    el('h2', {}, 'Measuring equipment'),
    sensorsTable(results, runDay),
    approval(results, run),
    el('footer', { class: 'cert-foot' },
      el('span', {}, 'This certificate refers only to the unit named above, as tested. It is void if altered.'),
      el('span', {}, 'Page 1 of 1')));
}

function notCertificate(run, results, reason) {
  return el('article', { class: 'sheet', id: 'sheet', 'data-certificate': 'false' },
    el('div', { class: 'not-certificate', id: 'not-certificate' }, `NOT A CERTIFICATE — ${reason}`,
      el('small', {}, 'No verdict is certified for this run. Its record is on the run page.')),
    el('h2', {}, 'Unit'),
    unitFacts(run, results),
    el('h2', {}, 'Run'),
    testFacts(run, results),
    el('footer', { class: 'cert-foot' }, el('span', {}, `Run ${run.id}`), el('span', {}, 'Not a certificate')));
}

async function main_() {
  if (!id) throw new Error('No run given: open this page as /certificate?id=<run id> (from the run page).');
  const detail = await readRun(`/api/runs/${encodeURIComponent(id)}`);
  const run = detail.run;
  const results = detail.results || {};
  const reason = notCertificateReason(run, results);
  document.title = reason ? `Not a certificate – ${run.id}` : `Certificate ${run.unit_serial || ''} ${run.id}`;
  message.hidden = true;
  main.append(reason ? notCertificate(run, results, reason) : certificate(run, results));
  document.body.dataset.ready = 'true';
}

main_().catch((e) => {
  message.hidden = false;
  message.className = 'message error';
  message.textContent = e.message || String(e);
});
