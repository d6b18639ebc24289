// The start form: unit serial, spec, procedure and Start first; the procedure's options
// (generated from GET /api/procedures) under "Advanced". A scan never starts a run (see
// serial_scan.js): Start needs a click or a key on the focused Start, and without a spec an
// in-page dialog asks first, because such a run gets no verdict. What a start would run is
// summarised beside Start. An API 400 whose detail names a key is shown beside that field.
import { get, post, ApiError } from './api.js';
import { SerialScan } from './serial_scan.js';

// The summary names this many of a procedure's options (its first, in schema order: the ones
// that shape the run), and every option changed from its default.
const KEY_OPTIONS = 2;

const $ = (id) => document.getElementById(id);

function el(tag, attrs = {}, text) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (v !== undefined && v !== null) e.setAttribute(k, v);
  }
  if (text !== undefined) e.textContent = text;
  return e;
}

function valueText(value, unit) {
  const text = Array.isArray(value) ? value.join(', ') : String(value);
  return unit ? `${text} ${unit}` : text;
}

export class StartForm {
  // onStarted(answer, request): a run was accepted; onSerial(serial): the serial entered changed.
  constructor({ onStarted, onSerial }) {
    this.form = $('start-form');
    this.onStarted = onStarted;
    this.onSerial = onSerial || (() => {});
    this.procedures = [];
    this.enabled = false;
    this.busy = false;
    // The form never submits itself: Enter in any of its fields does nothing here.
    this.form.addEventListener('submit', (e) => e.preventDefault());
    this.scan = new SerialScan({
      field: $('unit-serial'),
      start: $('start'),
      onScanned: () => this.changed(),
    });
    $('start').addEventListener('click', (e) => {
      // detail 0: a click made by a key; the one ending a scan does not count.
      if (e.detail === 0 && this.scan.justScanned()) return;
      this.requestStart();
    });
    $('procedure').addEventListener('change', () => {
      this.showOptions();
      this.changed();
    });
    // The options sit apart from the form, under "Advanced" below the progress and verdict.
    for (const part of [this.form, $('advanced')]) {
      part.addEventListener('input', () => this.changed());
      part.addEventListener('change', () => this.changed());
    }
    this.dialog = $('no-spec-dialog');
    $('start').addEventListener('focus', () => this.showSummary());
    $('start').addEventListener('blur', () => this.showSummary());
  }

  async load() {
    // The procedures come from the daemon's registry only (GET /api/procedures): a daemon that
    // does not serve it leaves the list empty, and nothing can start.
    try {
      this.procedures = (await get('/api/procedures')).procedures || [];
    } catch (_) {
      this.procedures = [];
    }
    const select = $('procedure');
    select.replaceChildren(...this.procedures.map((p) => el('option', { value: p.name }, p.title || p.name)));
    this.showOptions();
    try {
      const specs = (await get('/api/specs')).specs || [];
      const spec = $('spec');
      for (const s of specs) spec.append(el('option', { value: s.name }, `${s.name} — ${s.model || ''}`));
    } catch (_) {
      // no specs served: runs without a verdict
    }
    this.changed();
  }

  current() {
    const name = $('procedure').value;
    return this.procedures.find((p) => p.name === name) || { options: [] };
  }

  showOptions() {
    const p = this.current();
    $('procedure-description').textContent = p.description || '';
    const box = $('options');
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

  // The value a field holds, as sent; undefined for an empty number field.
  static fieldValue(input) {
    const type = input.dataset.type;
    if (type === 'boolean') return input.checked;
    const text = input.value.trim();
    if (type === 'number_list') {
      return text === '' ? [] : text.split(/[,\s]+/).map((x) => (Number.isFinite(Number(x)) ? Number(x) : x));
    }
    if (text === '') return undefined;
    return Number.isFinite(Number(text)) ? Number(text) : text;  // the daemon names a bad one
  }

  // Only options the operator changed are sent: the procedure's defaults stay the daemon's.
  options() {
    const out = {};
    for (const input of document.querySelectorAll('#options input')) {
      const value = StartForm.fieldValue(input);
      if (value === undefined) continue;
      if (JSON.stringify(value) !== JSON.stringify(JSON.parse(input.dataset.default))) out[input.name] = value;
    }
    return out;
  }

  request() {
    const body = { procedure: $('procedure').value, options: this.options() };
    const spec = $('spec').value;
    if (spec) body.spec = spec;
    const operator = $('operator').value.trim();
    if (operator) body.operator = operator;
    const serial = $('unit-serial').value.trim();
    if (serial) body.unit_serial = serial;
    return body;
  }

  changed() {
    this.onSerial($('unit-serial').value.trim());
    this.showSummary();
  }

  // What Start would run, beside it: procedure, its key options and the changed ones, spec,
  // serial.
  showSummary() {
    const p = this.current();
    const body = this.request();
    const rows = [['procedure', p.title || p.name || '—']];
    (p.options || []).forEach((o, i) => {
      const input = document.getElementById(`opt-${o.name}`);
      if (!input) return;
      const value = StartForm.fieldValue(input);
      const changed = Object.prototype.hasOwnProperty.call(body.options, o.name);
      if (i < KEY_OPTIONS || changed) {
        rows.push([o.name, value === undefined ? '(default)' : valueText(value, o.unit), changed]);
      }
    });
    rows.push(['spec', body.spec || 'none: no verdict', !body.spec]);
    rows.push(['unit serial', body.unit_serial || 'none entered', !body.unit_serial]);
    const dl = $('run-summary');
    dl.replaceChildren(...rows.flatMap(([k, v, marked]) => [
      el('dt', {}, k), el('dd', marked ? { class: 'marked' } : {}, v)]));
    $('start-hint').textContent = document.activeElement === $('start') && this.enabled
      ? 'Click Start, or press Space, to begin.' : '';
  }

  // Without a spec, the operator confirms that the run gets no verdict.
  async requestStart() {
    if (!this.enabled || this.busy) return;
    if (!$('spec').value && !(await this.confirmNoSpec())) {
      $('spec').focus();
      return;
    }
    await this.submit();
  }

  confirmNoSpec() {
    return new Promise((resolve) => {
      this.dialog.returnValue = '';
      this.dialog.addEventListener('close', () => resolve(this.dialog.returnValue === 'confirm'), { once: true });
      this.dialog.showModal();
      $('no-spec-cancel').focus();
    });
  }

  clearErrors() {
    for (const e of $('run-panel').querySelectorAll('.field-error')) e.textContent = '';
  }

  async submit() {
    this.clearErrors();
    const body = this.request();
    this.busy = true;
    $('start').disabled = true;
    try {
      const answer = await post('/api/runs', body);
      this.scan.markFinished();
      this.onStarted(answer, body);
    } catch (e) {
      this.showError(e);
    } finally {
      this.busy = false;
      $('start').disabled = !this.enabled;
    }
  }

  showError(e) {
    const key = e instanceof ApiError ? e.key : null;
    const beside = key ? $('run-panel').querySelector(`.field-error[data-key="${CSS.escape(key)}"]`) : null;
    if (beside && beside.closest('#advanced')) $('advanced').open = true;
    (beside || $('form-error')).textContent = e.message;
  }

  setEnabled(enabled) {
    this.enabled = enabled;
    $('start').disabled = !enabled || this.busy;
  }
}
