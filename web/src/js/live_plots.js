// The live plots: TE, input speed, torque and brake current against time, fed by the daemon's
// server-sent events (GET /api/live/stream). The daemon decimates by min and max per column;
// the page appends the rows and drops those older than the window, so 10 minutes of 1 kHz
// history stay a few thousand points per series. Time runs to the newest sample at 0 (a strip
// chart's "seconds ago"), so its tick labels stay short whatever the clock.
import { xAxis, yAxis } from './axis_style.js';

const HEIGHT = 210;
const SERIES = [
  { key: 'te_arcsec', el: 'plot-te', label: 'TE', unit: 'arcsec', scale: 1, stroke: '#c0392b' },
  { key: 'input_speed_rad_s', el: 'plot-speed', label: 'input speed', unit: 'rpm',
    scale: 60 / (2 * Math.PI), stroke: '#2471a3' },
  { key: 'torque_nm', el: 'plot-torque', label: 'torque', unit: 'N·m', scale: 1, stroke: '#1e8449' },
  { key: 'brake_current_a', el: 'plot-brake', label: 'brake current', unit: 'A', scale: 1,
    stroke: '#7d3c98' },
];

export class LivePlots {
  constructor({ onStatus, onFrame } = {}) {
    this.onStatus = onStatus || (() => {});
    this.onFrame = onFrame || (() => {});
    this.windowS = 60;
    this.t = [];
    this.values = SERIES.map(() => []);
    this.dirty = false;
    this.frames = 0;       // events received
    this.draws = 0;        // redraws done
    this.ticks = [];       // animation-frame times of the last second
    this.tickCount = 0;    // animation frames since the page opened
    this.fps = 0;
    this.plots = SERIES.map((s) => this.makePlot(s));
    requestAnimationFrame((now) => this.tick(now));
    window.addEventListener('resize', () => this.resize());
  }

  makePlot(s) {
    const el = document.getElementById(s.el);
    const opts = {
      width: Math.max(el.clientWidth, 300),
      height: HEIGHT,
      scales: { x: { time: false, range: () => [-this.windowS, 0] } },
      axes: [xAxis('time [s], 0 = newest sample'), yAxis(`${s.label} [${s.unit}]`)],
      series: [{ label: 't [s]', value: (u, v) => (v == null ? '–' : v.toFixed(2)) },
        { label: `${s.label} [${s.unit}]`, stroke: s.stroke, width: 1, spanGaps: false }],
      legend: { live: true },
    };
    return new uPlot(opts, [[], []], el);
  }

  resize() {
    SERIES.forEach((s, i) => {
      const el = document.getElementById(s.el);
      this.plots[i].setSize({ width: Math.max(el.clientWidth, 300), height: HEIGHT });
    });
  }

  columns() {
    const el = document.getElementById(SERIES[0].el);
    return Math.min(4000, Math.max(10, Math.round(el.clientWidth || 1000)));
  }

  connect(windowS) {
    if (windowS) this.windowS = windowS;
    if (this.source) this.source.close();
    this.clear();
    const url = `/api/live/stream?window_s=${this.windowS}&columns=${this.columns()}`;
    this.source = new EventSource(url);
    this.source.onmessage = (event) => this.take(JSON.parse(event.data));
    // The browser reconnects by itself after a dropped connection; a refusal (503: too many
    // live views open) ends the stream, and the page says so.
    this.source.onerror = () => {
      const fps = document.getElementById('fps');
      if (fps && this.source.readyState === EventSource.CLOSED) {
        fps.textContent = 'live view refused (too many open?): reload to retry';
      }
    };
  }

  clear() {
    this.t = [];
    this.values = SERIES.map(() => []);
    this.dirty = true;
  }

  take(frame) {
    this.frames += 1;
    if (frame.reset) this.clear();
    if (frame.status) this.onStatus(frame.status);
    const rows = frame.rows;
    if (rows && rows.t.length) {
      for (let i = 0; i < rows.t.length; i += 1) this.t.push(rows.t[i]);
      SERIES.forEach((s, k) => {
        const src = rows[s.key];
        const dst = this.values[k];
        for (let i = 0; i < src.length; i += 1) dst.push(src[i] === null ? null : src[i] * s.scale);
      });
      const oldest = this.t[this.t.length - 1] - this.windowS;
      let drop = 0;
      while (drop < this.t.length && this.t[drop] < oldest) drop += 1;
      if (drop > 0) {
        this.t.splice(0, drop);
        this.values.forEach((v) => v.splice(0, drop));
      }
      this.dirty = true;
    }
    this.onFrame(frame);
  }

  tick(now) {
    this.tickCount += 1;
    this.ticks.push(now);
    while (this.ticks.length && this.ticks[0] < now - 1000) this.ticks.shift();
    this.fps = this.ticks.length;
    if (now - (this.shownAt || 0) > 1000) {
      this.shownAt = now;
      const fps = document.getElementById('fps');
      if (fps) fps.textContent = `${this.fps} frames/s · ${this.t.length} points per plot`;
    }
    if (this.dirty || this.redrawEveryFrame) {  // the latter: the frame-rate benchmark's worst case
      this.dirty = false;
      this.draws += 1;
      const newest = this.t.length ? this.t[this.t.length - 1] : 0;
      const ago = this.t.map((t) => t - newest);
      SERIES.forEach((s, k) => this.plots[k].setData([ago, this.values[k]]));
    }
    requestAnimationFrame((n) => this.tick(n));
  }

  // For the browser tests and the frame-rate benchmark.
  stats() {
    return { frames: this.frames, draws: this.draws, fps: this.fps, ticks: this.tickCount,
      points: this.t.length,
      seconds: this.t.length ? this.t[this.t.length - 1] - this.t[0] : 0 };
  }
}
