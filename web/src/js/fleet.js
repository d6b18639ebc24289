// The fleet page (/fleet): one figure of one gear model across the benches of the results
// store (the lab's shared one, or this bench's own): its trend and its SPC, from GET
// /api/fleet/figures|runs|spc. The choice lives in the page's query, so a view can be
// bookmarked and Back works.
import { get } from './api.js';
import { el } from './dom.js';
import { trendSection, spcSection } from './fleet_charts.js';

const form = document.getElementById('fleet-form');
const message = document.getElementById('message');
const results = document.getElementById('results');
const FIELDS = ['model', 'figure', 'bench', 'direction', 'load', 'last', 'lsl', 'usl'];
let figures = [];

function fail(text) {
  message.hidden = false;
  message.className = 'message error';
  message.textContent = text;
}

function say(text) {
  message.hidden = false;
  message.className = 'message';
  message.textContent = text;
}

function fill(select, values, keep) {
  for (const v of values) select.append(el('option', { value: v }, v));
  if (keep) select.value = keep;
}

// The models and benches the newest runs name (the newest model first), and the figures.
async function choices(q) {
  const [f, runs, status] = await Promise.all([
    get('/api/fleet/figures'), get('/api/fleet/runs?limit=1000'), get('/api/status').catch(() => null)]);
  figures = f.figures;
  const store = status && status.results_store;
  document.getElementById('store').textContent = store
    ? (store.kind === 'postgresql' ? "The lab's shared results store (PostgreSQL)." : "This bench's own results store (no shared store configured).")
    : '';
  fill(form.elements.figure, figures.map((x) => x.name), q.get('figure') || 'static_te_p2p');
  if (!form.elements.figure.value) form.elements.figure.value = 'static_te_p2p';  // an unknown one
  for (const o of form.elements.figure.options) {
    const fig = figures.find((x) => x.name === o.value);
    o.textContent = `${fig.name} [${fig.unit}]`;
    o.title = fig.what;
  }
  const models = [...new Set(runs.runs.map((r) => r.gear_model).filter(Boolean))];
  const benches = [...new Set(runs.runs.map((r) => r.bench))].sort();
  document.getElementById('models').replaceChildren(...models.map((m) => el('option', { value: m })));
  fill(form.elements.bench, benches, q.get('bench') || '');
  for (const key of ['model', 'direction', 'load', 'last', 'lsl', 'usl']) form.elements[key].value = q.get(key) || '';
  if (!form.elements.model.value && models.length) form.elements.model.value = models[0];
  return { models, runs: runs.runs.length };
}

function query() {
  const q = new URLSearchParams();
  for (const key of FIELDS) {
    const value = (form.elements[key].value || '').trim();
    if (value) q.set(key, value);
  }
  return q;
}

function onePassOnly() {
  const staticP2p = form.elements.figure.value === 'static_te_p2p';
  form.elements.direction.disabled = !staticP2p;
  form.elements.load.disabled = !staticP2p;
}

async function show(push) {
  const q = query();
  if (push) history.pushState(null, '', `/fleet?${q}`);
  results.replaceChildren();
  delete document.body.dataset.ready;
  const model = q.get('model');
  const figure = figures.find((f) => f.name === q.get('figure')) || figures[0];
  if (!model) {
    say('Pick a gear model.');
    document.body.dataset.ready = 'true';
    return;
  }
  if (figure.name !== 'static_te_p2p') {
    q.delete('direction');
    q.delete('load');
  }
  say('Loading…');
  let answer;
  try {
    answer = await get(`/api/fleet/spc?${q}`);
  } catch (e) {
    fail(e.message);
    return;
  }
  if (!answer.points.length) {
    const where = q.get('bench') ? ` on bench ${q.get('bench')}` : '';
    const pass = q.get('direction') || q.get('load') ? ' in that pass' : '';
    say(`No complete runs of model ${model}${where} with ${figure.name}${pass}.`);
    document.body.dataset.ready = 'true';
    return;
  }
  message.hidden = true;
  const trend = trendSection(answer, figure, model);
  const spc = spcSection(answer, figure);
  results.append(trend.section, spc.section);
  trend.draw();
  spc.draw();
  document.body.dataset.ready = 'true';
}

async function start() {
  const q = new URLSearchParams(location.search);
  let found;
  try {
    found = await choices(q);
  } catch (e) {
    fail(e.message);
    return;
  }
  onePassOnly();
  if (!found.runs) {
    say('No runs in the results store yet: a finished run appears here.');
    document.body.dataset.ready = 'true';
    return;
  }
  if (!found.models.length) {
    say('No run in the results store names a gear model (runs without a product spec have none).');
    document.body.dataset.ready = 'true';
    return;
  }
  await show(false);
}

form.elements.figure.addEventListener('change', onePassOnly);
form.addEventListener('submit', (e) => {
  e.preventDefault();
  show(true);
});
window.addEventListener('popstate', () => {
  const q = new URLSearchParams(location.search);
  for (const key of FIELDS) form.elements[key].value = q.get(key) || (key === 'figure' ? 'static_te_p2p' : '');
  onePassOnly();
  show(false);
});
start();
