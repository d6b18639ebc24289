// The start form, generated from the procedures' options schema (GET /api/procedures) and the
// product specs (GET /api/specs). Enter in the unit serial field submits (a barcode scanner
// types the serial and presses Enter). An API 400 whose detail names a key is shown beside
// that field.
import { get, post, ApiError } from './api.js';

const FALLBACK = [
  { name: 'static', title: 'Static TE', options: [] },
  { name: 'dynamic', title: 'Dynamic TE', options: [] },
  { name: 'lost-motion', title: 'Lost motion', options: [] },
  { name: 'torsional', title: 'Torsional stiffness (locked output)', options: [] },
  { name: 'endurance', title: 'Endurance', options: [] },
];

function el(tag, attrs = {}, text) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (v !== undefined && v !== null) e.setAttribute(k, v);
  }
  if (text !== undefined) e.textContent = text;
  return e;
}

export class StartForm {
  constructor({ onStarted }) {
    this.form = document.getElementById('start-form');
    this.onStarted = onStarted;
    this.procedures = [];
    this.form.addEventListener('submit', (e) => {
      e.preventDefault();
      this.submit();
    });
    document.getElementById('procedure').addEventListener('change', () => this.showOptions());
  }

  async load() {
    try {
      this.procedures = (await get('/api/procedures')).procedures;
    } catch (_) {
      this.procedures = FALLBACK;  // an older daemon: the options keep their defaults
    }
    const select = document.getElementById('procedure');
    select.replaceChildren(...this.procedures.map((p) => el('option', { value: p.name }, p.title || p.name)));
    this.showOptions();
    try {
      const specs = (await get('/api/specs')).specs || [];
      const spec = document.getElementById('spec');
      for (const s of specs) spec.append(el('option', { value: s.name }, `${s.name} — ${s.model || ''}`));
    } catch (_) {
      // no specs served: runs without a verdict
    }
  }

  current() {
    const name = document.getElementById('procedure').value;
    return this.procedures.find((p) => p.name === name) || { options: [] };
  }

  showOptions() {
    const p = this.current();
    document.getElementById('procedure-description').textContent = p.description || '';
    const box = document.getElementById('options');
    box.replaceChildren();
    for (const o of p.options || []) {
      const id = `opt-${o.name}`;
      const label = el('label', { for: id, title: o.description || '' },
        `${o.name}${o.unit ? ` [${o.unit}]` : ''}`);
      let input;
      if (o.type === 'boolean') {
        input = el('input', { id, type: 'checkbox', name: o.name });
        input.checked = !!o.default;
      } else {
        input = el('input', { id, name: o.name, type: 'text', inputmode: 'decimal' });
        const d = o.default;
        input.value = d === undefined || d === null ? '' : (Array.isArray(d) ? d.join(', ') : String(d));
        const range = [];
        if (o.minimum !== undefined) range.push(`${o.exclusive_minimum ? '>' : '≥'} ${o.minimum}`);
        if (o.maximum !== undefined) range.push(`≤ ${o.maximum}`);
        input.placeholder = range.join(', ');
      }
      input.dataset.type = o.type;
      input.dataset.default = JSON.stringify(o.default === undefined ? null : o.default);
      const row = el('div', { class: 'option' });
      row.append(label, input, el('span', { class: 'field-error', 'data-key': o.name }));
      if (o.description) row.append(el('span', { class: 'hint' }, o.description));
      box.append(row);
    }
  }

  // Only options the operator changed are sent: the procedure's defaults stay the daemon's.
  options() {
    const out = {};
    for (const input of document.querySelectorAll('#options input')) {
      const type = input.dataset.type;
      const def = JSON.parse(input.dataset.default);
      let value;
      if (type === 'boolean') {
        value = input.checked;
      } else if (type === 'number_list') {
        const text = input.value.trim();
        value = text === '' ? [] : text.split(/[,\s]+/).map((x) => (Number.isFinite(Number(x)) ? Number(x) : x));
      } else {
        const text = input.value.trim();
        if (text === '') continue;
        value = Number.isFinite(Number(text)) ? Number(text) : text;  // the daemon names a bad one
      }
      if (JSON.stringify(value) !== JSON.stringify(def)) out[input.name] = value;
    }
    return out;
  }

  clearErrors() {
    for (const e of this.form.querySelectorAll('.field-error')) e.textContent = '';
  }

  async submit() {
    this.clearErrors();
    const body = { procedure: document.getElementById('procedure').value, options: this.options() };
    const spec = document.getElementById('spec').value;
    if (spec) body.spec = spec;
    const operator = document.getElementById('operator').value.trim();
    if (operator) body.operator = operator;
    const serial = document.getElementById('unit-serial').value.trim();
    if (serial) body.unit_serial = serial;
    const button = document.getElementById('start');
    button.disabled = true;
    try {
      const answer = await post('/api/runs', body);
      this.onStarted(answer);
    } catch (e) {
      this.showError(e);
    } finally {
      button.disabled = !this.enabled;
    }
  }

  showError(e) {
    const key = e instanceof ApiError ? e.key : null;
    const beside = key ? this.form.querySelector(`.field-error[data-key="${CSS.escape(key)}"]`) : null;
    (beside || document.getElementById('form-error')).textContent = e.message;
  }

  setEnabled(enabled) {
    this.enabled = enabled;
    document.getElementById('start').disabled = !enabled;
  }
}
