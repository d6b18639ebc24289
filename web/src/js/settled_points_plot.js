// During a static run: TE against output angle, a point at each settled position as the
// daemon reports it (/api/status run.points), one series per direction and load (catman's XY
// view). The points stay on screen after the run until the next run starts.
import { joinSeries, palette } from './plots.js';
import { xAxis, yAxis } from './axis_style.js';

const HEIGHT = 260;

function seriesKey(p) {
  return `${p.direction} · ${p.load_nm} N·m`;
}

export class SettledPointsPlot {
  constructor() {
    this.panel = document.getElementById('xy-panel');
    this.box = document.getElementById('plot-xy');
    this.plot = null;
    this.keys = [];
    this.count = 0;  // points drawn (the browser tests read it)
    this.runId = null;
    window.addEventListener('resize', () => {
      if (this.plot) this.plot.setSize({ width: this.width(), height: HEIGHT });
    });
  }

  width() {
    return Math.max(300, this.box.clientWidth || 600);
  }

  // A new run: the last run's points go.
  clear() {
    if (this.plot) this.plot.destroy();
    this.plot = null;
    this.keys = [];
    this.count = 0;
    this.panel.hidden = true;
  }

  show(run) {
    const points = (run && Array.isArray(run.points)) ? run.points : [];
    if (run && run.id !== this.runId) {
      this.runId = run.id;
      this.clear();
    }
    if (points.length === this.count) return;
    const keys = [...new Set(points.map(seriesKey))];
    if (!this.plot || keys.join('|') !== this.keys.join('|')) this.create(keys);
    const pairs = keys.map((k) => {
      const own = points.filter((p) => seriesKey(p) === k && p.te_arcsec !== null);
      return [own.map((p) => p.output_angle_deg), own.map((p) => p.te_arcsec)];
    });
    this.plot.setData(joinSeries(pairs));
    this.count = points.length;
    document.getElementById('xy-title').textContent =
      `TE against output angle: ${points.length} settled position${points.length === 1 ? '' : 's'}` +
      `${run && run.id ? ` (run ${run.id})` : ''}`;
  }

  create(keys) {
    if (this.plot) this.plot.destroy();
    this.keys = keys;
    this.panel.hidden = false;
    const loads = [...new Set(keys.map((k) => k.split(' · ')[1]))];
    this.plot = new uPlot({
      width: this.width(),
      height: HEIGHT,
      scales: { x: { time: false, range: [0, 360] } },
      axes: [{ ...xAxis('output angle [°]'), incrs: [15, 30, 45, 90], space: 40 },
        yAxis('TE [arcsec]')],
      series: [{ label: 'angle [°]', value: (u, v) => (v == null ? '–' : v.toFixed(1)) },
        ...keys.map((k) => {
          const color = palette[loads.indexOf(k.split(' · ')[1]) % palette.length];
          return {
            label: k,
            stroke: color,
            width: 1.5,
            dash: k.startsWith('reverse') ? [6, 4] : undefined,
            spanGaps: true,
            points: { show: true, size: 7, fill: color },
            value: (u, v) => (v == null ? '–' : `${v.toFixed(1)}″`),
          };
        })],
    }, [[], ...keys.map(() => [])], this.box);
  }
}
