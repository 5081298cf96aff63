// The selection brush's dab: every vertex within the brush radius of the hit
// point gets the brush weight, full in the core and fading out over the soft
// rim (softness = the rim's share of the radius). 'add' raises weights to the
// dab, 'subtract' lowers them to 1 - dab; both are idempotent, so painting
// over the same place twice changes nothing.
import { smoothstep } from '../selection/region-weights.js';

export function brushWeight(distance, radius, softness) {
  const hardRadius = radius * (1 - softness);
  if (distance <= hardRadius) return 1;
  return smoothstep((radius - distance) / (radius - hardRadius));
}

/** Paints one dab into `weights` (in place); returns how many vertices changed. */
export function paintDab(weights, picker, center, radius, softness, mode) {
  let changed = 0;
  picker.forEachVertexInSphere(center, radius, (vertex, distance) => {
    const dab = brushWeight(distance, radius, softness);
    const before = weights[vertex];
    weights[vertex] = mode === 'subtract' ? Math.min(before, 1 - dab) : Math.max(before, dab);
    if (weights[vertex] !== before) changed++;
  });
  return changed;
}

/** Dab centres from `from` to `to` spaced by `spacing`, so fast strokes leave no gaps. */
export function strokePoints(from, to, spacing) {
  const length = Math.hypot(to[0] - from[0], to[1] - from[1], to[2] - from[2]);
  const steps = Math.max(1, Math.ceil(length / spacing));
  const points = [];
  for (let k = 1; k <= steps; k++) {
    const t = k / steps;
    points.push([0, 1, 2].map((axis) => from[axis] + (to[axis] - from[axis]) * t));
  }
  return points;
}
