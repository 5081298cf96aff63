// Colours of the compression-error maps, shared by the 2D pattern view and
// the legend: white at no error, through amber to red at `range` and beyond
// (an error is a size, |achieved / wanted - 1|, so the scale is one-sided).
// NaN (a degenerate triangle, nothing to measure) is grey.
const STOPS = [
  [0.0, [245, 245, 240]],
  [0.5, [250, 190, 70]],
  [1.0, [205, 35, 30]],
];

export function heatColor(error, range) {
  if (!Number.isFinite(error)) return 'rgb(150,150,150)';
  const t = Math.min(Math.max(error / range, 0), 1);
  const upper = STOPS.findIndex(([stop]) => stop >= t);
  if (upper <= 0) return rgb(STOPS[0][1]);
  const [t0, c0] = STOPS[upper - 1];
  const [t1, c1] = STOPS[upper];
  const f = (t - t0) / (t1 - t0);
  return rgb(c0.map((value, k) => value + f * (c1[k] - value)));
}

function rgb([r, g, b]) {
  return `rgb(${Math.round(r)},${Math.round(g)},${Math.round(b)})`;
}
