// The history page (/history): runs filtered by unit serial (a prefix: "0042" finds "0042-A"),
// procedure, spec, verdict, status and date, a page at a time (GET /api/runs with offset/limit;
// total when the API gives it), with links to each run's page and exports; tick two or more to compare them (/compare?ids=...).
import { get } from './api.js';
import { el, verdictOf, specName } from './dom.js';
import { utcSeconds } from './figures.js';

const form = document.getElementById('filters');
const body = document.querySelector('#runs tbody');
const message = document.getElementById('message');
const pageText = document.getElementById('page');
const prev = document.getElementById('prev');
const next = document.getElementById('next');
const limitSelect = document.getElementById('limit');
const compare = document.getElementById('compare');
const FILTERS = ['unit', 'procedure', 'spec', 'verdict', 'status', 'from', 'to'];
const selected = new Set();
let offset = 0;

// The filters live in the page's own query, so a filtered view can be bookmarked and Back works.
function readLocation() {
  const q = new URLSearchParams(location.search);
  for (const key of FILTERS) if (form.elements[key]) form.elements[key].value = q.get(key) || '';
  offset = Math.max(0, parseInt(q.get('offset') || '0', 10) || 0);
  const limit = q.get('limit');
  if (limit && [...limitSelect.options].some((o) => o.value === limit)) limitSelect.value = limit;
}

function query() {
  const q = new URLSearchParams();
  for (const key of FILTERS) {
    const value = (form.elements[key].value || '').trim();
    if (value) q.set(key, value);
  }
  if (offset > 0) q.set('offset', String(offset));
  q.set('limit', limitSelect.value);
  return q;
}

function row(run) {
  const verdict = verdictOf(run, null);
  const box = el('input', { type: 'checkbox', value: run.id, 'aria-label': `select ${run.id}`, checked: selected.has(run.id) });
  box.addEventListener('change', () => {
    if (box.checked) selected.add(run.id);
    else selected.delete(run.id);
    updateCompare();
  });
  const api = `/api/runs/${encodeURIComponent(run.id)}`;
  return el('tr', { 'data-id': run.id },
    el('td', {}, box),
    el('td', {}, el('a', { href: `/run?id=${encodeURIComponent(run.id)}` }, utcSeconds(run.started_at || run.id).replace(' UTC', ''))),
    el('td', {}, run.unit_serial || '–'),
    el('td', {}, run.procedure),
    el('td', {}, specName(run, null) || '–'),
    el('td', {}, el('span', { class: `verdict-small verdict-${(verdict || 'none').toLowerCase()}` }, verdict || '–')),
    el('td', { class: `status-${run.status}`, title: run.reason || '' }, run.status + (run.reason ? ` (${run.reason})` : '')),
    el('td', {}, el('a', { href: api }, 'JSON'), ' ', el('a', { href: `${api}/samples?from=0&limit=1000` }, 'samples')));
}

function updateCompare() {
  compare.disabled = selected.size < 2;
  compare.textContent = selected.size >= 2 ? `Compare ${selected.size} selected` : 'Compare selected';
}

async function load(push) {
  const q = query();
  if (push) history.pushState(null, '', `/history?${q}`);
  message.className = 'message';
  message.textContent = 'Loading…';
  let answer;
  try {
    answer = await get(`/api/runs?${q}`);
  } catch (e) {
    message.className = 'message error';
    message.textContent = e.message;
    body.replaceChildren();
    return;
  }
  const runs = answer.runs || [];
  const limit = Number(limitSelect.value);
  const total = Number.isFinite(answer.total) ? answer.total : null;
  body.replaceChildren(...runs.map(row));
  message.textContent = runs.length ? '' : 'No runs match these filters.';
  const last = offset + runs.length;
  pageText.textContent = runs.length ? `${offset + 1}–${last}${total != null ? ` of ${total}` : ''}` : '';
  prev.disabled = offset === 0;
  next.disabled = total != null ? last >= total : runs.length < limit;
  document.body.dataset.ready = 'true';
}

form.addEventListener('submit', (e) => {
  e.preventDefault();
  offset = 0;
  load(true);
});
form.addEventListener('reset', () => setTimeout(() => { offset = 0; load(true); }));
prev.addEventListener('click', () => { offset = Math.max(0, offset - Number(limitSelect.value)); load(true); });
next.addEventListener('click', () => { offset += Number(limitSelect.value); load(true); });
limitSelect.addEventListener('change', () => { offset = 0; load(true); });
compare.addEventListener('click', () => {
  location.href = `/compare?ids=${[...selected].map(encodeURIComponent).join(',')}`;
});
window.addEventListener('popstate', () => { readLocation(); load(false); });

// The procedures come from the daemon's registry (GET /api/procedures), never from a list here.
async function fillProcedures() {
  try {
    const select = form.elements.procedure;
    for (const p of (await get('/api/procedures')).procedures || []) {
      select.append(el('option', { value: p.name }, p.name));
    }
  } catch (_) {
    // an older daemon: "any" only; the filter still takes a name from the page's query
  }
}

fillProcedures().finally(() => {
  readLocation();
  updateCompare();
  load(false);
});
