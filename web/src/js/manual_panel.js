// The manual panel (issue #21): jog the input while a button is held, go to an output angle,
// set a brake torque, servo on/off, and the servo and brake in plain words.
//
// Dead-man: while ◀ or ▶ is held the page repeats the jog every KEEP_ALIVE_MS; the daemon stops
// the input when the repeats stop for its jog timeout (a lost connection, a frozen page). The
// page also sends stop itself on release, pointer cancel, leaving the button, losing focus and
// the tab being hidden, so a release stops at once instead of at the timeout. While the servo
// is held or a go-to runs, the page sends keep-alives; without them the daemon switches the
// servo off (go-to: trips the bench, the only way to interrupt a profile move).
import { post, get, ApiError } from './api.js';
import { el } from './dom.js';

const KEEP_ALIVE_MS = 100;
const HOLD_ALIVE_MS = 1000;
const STATUS_MS = 250;
const GOING_GRACE_MS = 1500;

class ManualPanel {
  constructor(root) {
    this.root = root;
    this.jogging = 0; // the direction held: -1, 0 or 1
    this.status = null;
    this.lastAlive = 0;
    this.goingSince = 0;
    this.build();
    this.bind();
    setInterval(() => this.tick(), KEEP_ALIVE_MS);
    setInterval(() => this.refresh(), STATUS_MS);
    this.refresh();
  }

  build() {
    const button = (id, text, label) => el('button', { id, type: 'button', class: 'jog', 'aria-label': label }, text);
    this.servoWords = el('strong', { id: 'manual-servo' }, '…');
    this.brakeWords = el('span', { id: 'manual-brake' }, '');
    this.outputWords = el('span', { id: 'manual-output' }, '');
    this.reverse = button('jog-reverse', '◀', 'jog reverse (hold)');
    this.forward = button('jog-forward', '▶', 'jog forward (hold)');
    this.speed = el('input', { id: 'jog-speed', type: 'number', min: '1', max: '60', step: '1', value: '30', inputmode: 'decimal' });
    this.angle = el('input', { id: 'goto-angle', type: 'number', step: '0.1', value: '0', inputmode: 'decimal' });
    this.torque = el('input', { id: 'brake-torque', type: 'number', min: '0', step: '0.1', value: '0', inputmode: 'decimal' });
    this.servo = el('button', { id: 'servo-toggle', type: 'button', class: 'servo' }, 'Servo on');
    this.note = el('p', { id: 'manual-note', class: 'hint' });
    this.error = el('p', { id: 'manual-error', class: 'field-error', role: 'alert' });
    this.limits = el('span', { id: 'manual-limits', class: 'hint' });
    this.goto = el('form', { id: 'manual-goto', class: 'manual-row' },
      el('label', {}, 'Go to output angle ', this.angle, ' °'), el('button', { type: 'submit' }, 'Go'));
    this.brakeForm = el('form', { id: 'manual-brake-form', class: 'manual-row' },
      el('label', {}, 'Brake torque ', this.torque, ' N·m'), el('button', { type: 'submit' }, 'Set'));
    this.root.replaceChildren(
      el('h2', {}, 'Manual'),
      el('div', { class: 'manual-state', 'aria-live': 'polite' }, 'Servo: ', this.servoWords, ' · ', this.brakeWords, ' · ', this.outputWords),
      el('div', { class: 'manual-row' }, this.servo),
      el('div', { class: 'manual-row jog-row' }, this.reverse,
        el('label', {}, 'Speed ', this.speed, ' rpm'), this.forward),
      el('p', { class: 'hint' }, 'Hold ◀ or ▶ (or Space on it) to turn the input; it stops when released. ', this.limits),
      this.goto, this.brakeForm, this.note, this.error);
    this.controls = [this.reverse, this.forward, this.speed, this.angle, this.torque, this.servo,
      ...this.goto.querySelectorAll('button'), ...this.brakeForm.querySelectorAll('button')];
  }

  bind() {
    for (const [button, direction] of [[this.reverse, -1], [this.forward, 1]]) {
      button.addEventListener('pointerdown', (e) => {
        if (e.button !== 0) return;
        this.presses = (this.presses || 0) + 1; // for the browser test's diagnostics
        button.setPointerCapture(e.pointerId);
        this.startJog(direction);
      });
      for (const type of ['pointerup', 'pointercancel', 'lostpointercapture']) {
        button.addEventListener(type, () => this.stopJog(type));
      }
      button.addEventListener('keydown', (e) => {
        if ((e.key === ' ' || e.key === 'Enter') && !e.repeat) {
          e.preventDefault();
          this.startJog(direction);
        }
      });
      button.addEventListener('keyup', (e) => {
        if (e.key === ' ' || e.key === 'Enter') {
          e.preventDefault();
          this.stopJog('keyup');
        }
      });
      // Only this button's own jog: pressing the other one moves focus away from this one.
      button.addEventListener('blur', () => {
        if (this.jogging === direction) this.stopJog('button blur');
      });
      button.addEventListener('contextmenu', (e) => e.preventDefault());
    }
    window.addEventListener('blur', () => this.stopJog('window blur'));
    window.addEventListener('pagehide', () => this.stopJog('pagehide'));
    document.addEventListener('visibilitychange', () => {
      if (document.hidden) this.stopJog('hidden');
    });
    this.servo.addEventListener('click', () => {
      const on = !(this.status && this.status.manual && this.status.manual.servo_on);
      this.send('servo', { on });
    });
    this.goto.addEventListener('submit', async (e) => {
      e.preventDefault();
      // Keep-alives from the request on: the status that shows the go-to may come later than
      // the daemon's timeout.
      this.goingSince = Date.now();
      if (!await this.send('goto', { angle_deg: Number(this.angle.value), speed_rpm: this.speedValue() })) {
        this.goingSince = 0;
      }
    });
    this.brakeForm.addEventListener('submit', (e) => {
      e.preventDefault();
      this.send('brake', { torque_nm: Number(this.torque.value) });
    });
  }

  speedValue() {
    return this.speed.value === '' ? NaN : Number(this.speed.value);
  }

  startJog(direction) {
    if (this.jogging === direction) return;
    this.jogging = direction;
    this.root.classList.add('jogging');
    this.sendJog();
  }

  // `cause` is kept for the browser test's diagnostics: which event ended a hold.
  stopJog(cause) {
    if (this.jogging === 0) return;
    this.jogging = 0;
    this.releasedAt = Date.now(); // for the browser test's stop latency
    this.stopCause = cause;
    this.root.classList.remove('jogging');
    this.send('stop', {});
  }

  async sendJog() {
    const direction = this.jogging;
    if (direction === 0) return;
    const speed = this.speedValue();
    try {
      await post('/api/manual/jog', { speed_rpm: direction * (Number.isFinite(speed) ? speed : NaN) });
      this.error.textContent = '';
    } catch (e) {
      // A refused jog ends the hold: the operator has to press again after fixing it.
      this.jogging = 0;
      this.stopCause = `refused: ${e.message}`;
      this.root.classList.remove('jogging');
      this.showError(e);
    }
  }

  async send(action, body) {
    try {
      const answer = await post(`/api/manual/${action}`, body);
      // A release's stop must not wipe the refusal of the jog it ends.
      if (action !== 'stop') this.error.textContent = '';
      if (answer && answer.manual && this.status) this.status.manual = answer.manual;
      this.refresh();
      return true;
    } catch (e) {
      this.showError(e);
      return false;
    }
  }

  showError(e) {
    if (e instanceof ApiError && e.status === 401) {
      this.error.textContent = 'Log in to move the bench.';
    } else {
      this.error.textContent = e.message;
    }
  }

  // Every KEEP_ALIVE_MS: the jog's repeat while held; keep-alives while the panel holds
  // something (every HOLD_ALIVE_MS) or a go-to runs (every tick).
  tick() {
    if (this.jogging !== 0) {
      this.sendJog();
      return;
    }
    const m = this.status && this.status.manual;
    if (!m) return;
    const going = (m.goto_deg !== null && m.goto_deg !== undefined) ||
      Date.now() - this.goingSince < GOING_GRACE_MS;
    const now = Date.now();
    if (going || (m.servo_on && now - this.lastAlive >= HOLD_ALIVE_MS)) {
      this.lastAlive = now;
      post('/api/manual/alive', {}).catch(() => {});
    }
  }

  async refresh() {
    try {
      this.show(await get('/api/status'));
    } catch (_) {
      this.servoWords.textContent = 'daemon not reachable';
    }
  }

  show(s) {
    this.status = s;
    const m = s.manual || {};
    this.servoWords.textContent = s.servo || '—';
    this.brakeWords.textContent = s.brake || '';
    this.root.dataset.servo = s.servo || '';
    const out = s.latest && s.latest.theta_out_rad;
    // The output's angle within its turn, as a go-to takes it.
    this.outputWords.textContent = typeof out === 'number'
      ? `output at ${((((out * 180) / Math.PI) % 360 + 360) % 360).toFixed(1)}°` : '';
    if (m.max_speed_rpm) this.speed.max = String(m.max_speed_rpm);
    if (m.max_brake_torque_nm !== undefined) this.torque.max = String(m.max_brake_torque_nm);
    this.limits.textContent = m.max_speed_rpm
      ? `Up to ${m.max_speed_rpm} rpm at the input; brake up to ${m.max_brake_torque_nm} N·m.` : '';
    this.servo.textContent = m.servo_on ? 'Servo off' : 'Servo on';
    this.servo.classList.toggle('on', Boolean(m.servo_on));
    const blocked = s.run ? 'A run is active: the manual panel waits until it has ended.'
      : s.state === 'fault' ? 'The bench is in fault: reset it first.'
        : s.state === 'idle' ? 'No bench connected.' : '';
    // Why manual control last ended, while it matters: until the panel is used again.
    const idle = !m.servo_on && s.servo === 'servo off';
    this.note.textContent = blocked || (idle && m.last_stop ? `Last stop: ${m.last_stop}` : '');
    for (const c of this.controls) c.disabled = Boolean(blocked) && c !== this.servo;
    this.servo.disabled = Boolean(blocked) && !m.servo_on;
    if (blocked) this.stopJog(blocked);
  }
}

const root = document.getElementById('manual-panel');
if (root) window.wavebenchManual = new ManualPanel(root);
