// Axes the console's live plots share: a label with the unit, enough ticks to read a value off
// (at least four over a plot's height), and a tick-label column as wide as its longest label,
// so "-1250" or "600" is never clipped.
const CHAR_PX = 7;   // about one digit at uPlot's 12 px axis font
const TICK_PX = 14;  // the tick and the gap beside the labels

function labelWidth(self, values) {
  if (!values || !values.length) return 40;
  const longest = Math.max(...values.map((v) => String(v ?? '').length));
  return Math.max(40, longest * CHAR_PX + TICK_PX);
}

export function xAxis(label) {
  return { label, stroke: '#333', grid: { stroke: '#e4e4e4' }, space: 60, size: 40 };
}

// space: the least number of pixels between y ticks (uPlot's default, 30, leaves one or two
// ticks on a short plot).
export function yAxis(label) {
  return { label, stroke: '#333', grid: { stroke: '#e4e4e4' }, space: 18, size: labelWidth };
}
