// The selection brush's dab: every vertex within the brush radius of the hit
// point gets the brush weight, full in the middle and fading out over the soft
// rim (softness = the rim's share of the radius). The dab is the brush's own
// shape (the ball the cursor shows, found by a BVH query near the pointer),
// not a core selection rule: it stays on the page so the stroke repaints on
// every pointer move. It combines with the weights by the core's rule for
// Session.select's modes ('add' = max(old, dab), 'subtract' = min(old,
// 1 - dab)); wasm/test/brush-parity.test.mjs pins that to the core. Both are
// idempotent, so painting over the same place twice changes nothing. The
// stroke is committed with setSelection, which the core checks.

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

function smoothstep(x) {
  const t = Math.min(Math.max(x, 0), 1);
  return t * t * (3 - 2 * t);
}
