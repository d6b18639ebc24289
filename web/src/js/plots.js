// uPlot with the pages' conventions: drag to zoom the x range, the wheel zooms about the
// cursor, shift-drag (or the middle button) pans, double-click resets; the legend shows the
// values under the cursor. uPlot is the global from /vendor/uPlot.iife.min.js.
const uPlot = window.uPlot;

export const palette = ['#1f5fa8', '#c4461b', '#2e8540', '#7b3fa0', '#b8860b', '#0f7c8a', '#a0314f', '#555'];

const plots = new Set();

// Text labels at data points (named spectrum peaks): [{x, y, text}].
function labelsPlugin(labels) {
  return {
    hooks: {
      draw: (u) => {
        const ctx = u.ctx;
        ctx.save();
        ctx.font = `${Math.round(11 * devicePixelRatio)}px sans-serif`;
        ctx.fillStyle = '#222';
        ctx.textAlign = 'center';
        for (const l of labels()) {
          if (l.x < u.scales.x.min || l.x > u.scales.x.max) continue;
          if (u.scales.y.distr === 3 && !(l.y > 0)) continue;
          const x = u.valToPos(l.x, 'x', true);
          const y = u.valToPos(l.y, 'y', true);
          if (!Number.isFinite(x) || !Number.isFinite(y)) continue;
          ctx.fillStyle = l.color || '#222';
          ctx.fillText(l.text, x, Math.max(y - 6 * devicePixelRatio, 12 * devicePixelRatio));
        }
        ctx.restore();
      },
    },
  };
}

function wheelAndPanPlugin() {
  return {
    hooks: {
      ready: (u) => {
        const over = u.over;
        over.addEventListener('wheel', (e) => {
          e.preventDefault();
          const { min, max } = u.scales.x;
          const at = u.posToVal(e.offsetX, 'x');
          const k = e.deltaY < 0 ? 0.8 : 1.25;
          u.setScale('x', { min: at - (at - min) * k, max: at + (max - at) * k });
        }, { passive: false });
        over.addEventListener('mousedown', (e) => {
          if (!(e.shiftKey || e.button === 1)) return;
          e.preventDefault();
          e.stopPropagation();
          const x0 = e.clientX;
          const { min, max } = u.scales.x;
          const perPx = (max - min) / over.clientWidth;
          const move = (m) => u.setScale('x', { min: min - (m.clientX - x0) * perPx, max: max - (m.clientX - x0) * perPx });
          const up = () => {
            document.removeEventListener('mousemove', move);
            document.removeEventListener('mouseup', up);
          };
          document.addEventListener('mousemove', move);
          document.addEventListener('mouseup', up);
        }, true);
      },
    },
  };
}

// Tick labels with the decimals the tick step needs: a figure that varies in its fourth
// decimal gets four (uPlot's default stops at three, and the ticks repeat), and 600 reads
// "600", not "600.0".
export function stepTicks(u, splits, axis, space, step) {
  if (!(step > 0)) return splits.map((v) => (v == null ? '' : String(v)));
  let decimals = Math.max(0, -Math.floor(Math.log10(step)));
  const scaled = step * 10 ** decimals;
  if (Math.abs(scaled - Math.round(scaled)) > 1e-6) decimals += 1;
  return splits.map((v) => (v == null ? '' : v.toFixed(Math.min(decimals, 12))));
}

const pad = (n) => String(n).padStart(2, '0');
const isoDay = (d) => `${d.getUTCFullYear()}-${pad(d.getUTCMonth() + 1)}-${pad(d.getUTCDate())}`;
const isoMinute = (d) => `${pad(d.getUTCHours())}:${pad(d.getUTCMinutes())}`;

// Time ticks in UTC, ISO style (24 h): dates when the ticks are days apart, else hours and
// minutes, with the date under the first tick of each day.
export function timeTicks(u, splits, axis, space, step) {
  let day = null;
  return splits.map((s) => {
    if (s == null) return '';
    const d = new Date(s * 1000);
    if (step >= 86400) return isoDay(d);
    const today = isoDay(d);
    // Ticks under a minute apart need their seconds, or neighbours read the same.
    const time = step < 60 ? d.toISOString().slice(11, 19) : isoMinute(d);
    const label = today !== day ? `${time}\n${today}` : time;
    day = today;
    return label;
  });
}

// "2026-11-27 15:04:05" (UTC) for the legend of a time axis.
export const timeValue = (u, v) => (v == null ? '–' : `${isoDay(new Date(v * 1000))} ${new Date(v * 1000).toISOString().slice(11, 19)}`);

const AXIS_FONT = '12px system-ui, "DejaVu Sans", sans-serif';
const LABEL_FONT = 'bold 12px system-ui, "DejaVu Sans", sans-serif';
let measure = null;

// The y axis as wide as its widest tick label (plus the axis title): labels are never clipped.
function axisSize(u, values, axisIdx, cycleNum) {
  if (cycleNum > 2 || !values) return u.axes[axisIdx]._size || 60;
  if (!measure) measure = document.createElement('canvas').getContext('2d');
  measure.font = AXIS_FONT;
  const widest = Math.max(0, ...values.map((v) => measure.measureText(String(v ?? '')).width));
  return Math.ceil(widest) + 12 + 22;  // ticks + gap, and the rotated axis title
}

// series: [{label, color?, points?: true, width?, dash?, marker?: 'ring'}], data: [x, y1, ...].
// Options: xLabel, yLabel, logY, height, labels (() => [{x, y, text}]), onZoom(min, max)
// (called, debounced, after the x range changes), yValues (uPlot's axis `values`: the y tick
// labels; stepTicks by default), xIncrs (the x tick steps allowed), xTime (x is seconds since
// 1970: dates and times in UTC on the axis). A 'ring' marker is a large open circle: the
// points a chart marks (out of spec), told apart from the others by shape, not colour alone.
export function makePlot(container, { xLabel, yLabel, series, data, logY, height, labels, onZoom, yValues, xIncrs, xTime }) {
  const axis = { stroke: '#333', grid: { stroke: '#e4e4e4' }, ticks: { stroke: '#bbb' }, font: AXIS_FONT, labelFont: LABEL_FONT };
  const opts = {
    width: Math.max(300, container.clientWidth || 800),
    height: height || 300,
    cursor: { drag: { x: true, y: false, setScale: true } },
    scales: { x: { time: !!xTime }, y: logY ? { distr: 3 } : {} },
    axes: [{ ...axis, label: xLabel, space: 70, size: xTime ? 62 : 50, ...(xIncrs ? { incrs: xIncrs } : {}), values: xTime ? timeTicks : stepTicks },
      { ...axis, label: yLabel, space: 28, size: axisSize, ...(logY ? {} : { values: yValues || stepTicks }) }],
    series: [{ label: xLabel, ...(xTime ? { value: timeValue } : {}) }, ...series.map((s, i) => ({
      label: s.label,
      stroke: s.color || palette[i % palette.length],
      width: s.width || 1.5,
      dash: s.dash,
      spanGaps: s.spanGaps ?? false,
      points: s.marker === 'ring'
        ? { show: true, size: 13, width: 2.5, fill: '#fff', stroke: s.color || '#b3261e' }
        : s.points ? { show: true, size: 6, fill: s.color || palette[i % palette.length] } : { show: false },
      ...(s.points && !s.line ? { paths: () => null } : {}),
      value: (u, v) => (v == null ? '–' : Number(v).toPrecision(5)),
    }))],
    plugins: [wheelAndPanPlugin(), ...(labels ? [labelsPlugin(labels)] : [])],
    hooks: {},
  };
  if (onZoom) {
    let timer = null;
    opts.hooks.setScale = [(u, key) => {
      if (key !== 'x') return;
      clearTimeout(timer);
      timer = setTimeout(() => onZoom(u.scales.x.min, u.scales.x.max), 150);
    }];
  }
  const u = new uPlot(opts, data, container);
  plots.add(u);
  return u;
}

export function removePlot(u) {
  plots.delete(u);
  u.destroy();
}

function fit(widthOf) {
  for (const u of plots) {
    const w = widthOf(u);
    if (w > 0 && Math.abs(w - u.width) > 2) u.setSize({ width: w, height: u.height });
  }
}

const fitToContainers = () => fit((u) => u.root.parentElement.clientWidth);
window.addEventListener('resize', () => requestAnimationFrame(fitToContainers));
// On paper, a plot spans the A4 text width (170 mm at 96 px/in).
window.addEventListener('beforeprint', () => fit(() => 640));
window.addEventListener('afterprint', fitToContainers);

// Series that do not share x values, on one x axis (uPlot wants one ascending x array): each
// series is null where another one has its points (draw them with spanGaps). Repeated x values
// are kept, unlike uPlot.join.
export function joinSeries(pairs) {
  const rows = [];
  pairs.forEach(([x, y], k) => x.forEach((xv, i) => {
    if (xv != null && Number.isFinite(xv)) rows.push([xv, k, y[i]]);
  }));
  rows.sort((a, b) => a[0] - b[0] || a[1] - b[1]);
  const data = [rows.map((r) => r[0]), ...pairs.map(() => new Array(rows.length).fill(null))];
  rows.forEach((r, i) => { data[r[1] + 1][i] = r[2]; });
  return data;
}
