// The selection brush paints on the page (web/src/interaction/selection-brush.js)
// so that a stroke repaints on every pointer move; it must combine its dabs with
// the selection exactly as the core's Session.select modes do (add = max(old,
// new), subtract = min(old, 1 - new)). Here the same dab goes through both, on
// a real mesh and a soft starting selection, and the weights must be equal.
import assert from 'node:assert/strict';
import { before, test } from 'node:test';

import { brushWeight, paintDab } from '../../web/src/interaction/selection-brush.js';
import { boundingBox, loadAnisoform, sessionWith } from '../node-support.mjs';

let wasm;
before(async () => {
  ({ wasm } = await loadAnisoform());
});

// The picker's sphere query without its BVH: every vertex within `radius`.
function bruteForcePicker(positions) {
  return {
    forEachVertexInSphere(center, radius, visit) {
      for (let v = 0; v < positions.length / 3; v++) {
        const d = Math.hypot(positions[3 * v] - center[0], positions[3 * v + 1] - center[1], positions[3 * v + 2] - center[2]);
        if (d <= radius) visit(v, d);
      }
    },
  };
}

for (const mode of ['add', 'subtract']) {
  test(`a brush dab (${mode}) gives the weights of the core's select with mode '${mode}'`, () => {
    const session = sessionWith(wasm, 'closed/bunny_npm.obj');
    try {
      const positions = session.positions().slice();
      const { min, max, diagonal } = boundingBox(positions);
      const middle = [0, 1, 2].map((k) => (min[k] + max[k]) / 2);
      // A soft starting selection, so both max and min have something to decide.
      session.select({ sphere: { center: middle, radius: 0.2 * diagonal } }, { falloff: 0.2 * diagonal });
      const start = session.selection().slice();
      assert.ok(start.some((w) => w > 0 && w < 1), 'the starting selection has soft weights');

      const page = start.slice();
      // Centred on a vertex of the soft border: the dab meets weights above,
      // below and between its own.
      const border = start.findIndex((w) => w > 0.3 && w < 0.7);
      const center = Array.from(positions.slice(3 * border, 3 * border + 3));
      const dab = new Map();
      const picker = bruteForcePicker(positions);
      const recorder = {
        forEachVertexInSphere: (c, r, visit) => picker.forEachVertexInSphere(c, r, (v, d) => {
          visit(v, d);
          dab.set(v, d);
        }),
      };
      const radius = 0.15 * diagonal;
      const softness = 0.5;
      const changed = paintDab(page, recorder, center, radius, softness, mode);
      assert.ok(changed > 10, `the dab changed ${changed} weights`);

      // The same dab as the core's weighted vertex region: weight 1 inside the
      // hard core, fading over the rim, exactly as the brush weighs it.
      const vertices = [...dab.keys()];
      const weights = vertices.map((v) => brushWeight(dab.get(v), radius, softness));
      session.select({ vertices, weights }, { mode });
      const core = session.selection().slice();
      let differ = 0;
      for (let v = 0; v < core.length; v++) differ += core[v] !== page[v];
      assert.equal(differ, 0, `${differ} of ${core.length} weights differ between the brush and the core`);
    } finally {
      session.delete();
    }
  });
}
