// A drag on a surface seen at an angle means the tangent direction seen along
// the drag: the arrows' JS (web/src/interaction/screen-drag.js
// tangentDragVector) and the core's 'screen' direction with camera.normal
// follow one rule. Projected along the normal instead, a 45° drag on the
// default view stretched along a line seen at 60°, and a horizontal arrow
// drag drew an arrow at about -20°.
import assert from 'node:assert/strict';
import { after, before, test } from 'node:test';
import { PerspectiveCamera, Vector3 } from '../../web/node_modules/three/build/three.module.js';

import { tangentDragVector } from '../../web/src/interaction/screen-drag.js';
import { loadAnisoform, sessionWith } from '../node-support.mjs';

let wasm;
let session;
before(async () => {
  ({ wasm } = await loadAnisoform());
  session = sessionWith(wasm, 'open/plane.off');  // the plane y = 0
});
after(() => session?.delete());

const viewport = [0, 0, 900, 600];

function cameraAt(position) {
  const camera = new PerspectiveCamera(45, viewport[2] / viewport[3], 0.1, 100);
  camera.position.set(...position);
  camera.lookAt(0, 0, 0);
  camera.updateMatrixWorld();
  camera.updateProjectionMatrix();
  const state = {
    view: Array.from(camera.matrixWorldInverse.elements),
    projection: Array.from(camera.projectionMatrix.elements),
    viewport,
  };
  return { camera, state };
}

function toPixels(camera, point) {
  const ndc = new Vector3(...point).project(camera);
  return [(ndc.x + 1) / 2 * viewport[2], (1 - ndc.y) / 2 * viewport[3]];
}

/** Signed angle (degrees) of a pixel vector, y up as seen. */
const screenAngle = ([dx, dy]) => (Math.atan2(-dy, dx) * 180) / Math.PI;

const unit = (v) => {
  const length = Math.hypot(...v);
  return v.map((x) => x / length);
};

for (const position of [[3, 4, -3], [-2, 1.5, 5], [0.5, 6, 0.2]]) {
  test(`a drag on the plane seen from ${position} is seen along the drag, in JS and in the core`, () => {
    const { camera, state } = cameraAt(position);
    const anchor = [0, 0, 0];
    const normal = [0, 2, 0];
    const from = toPixels(camera, anchor);
    for (const degrees of [0, 30, 45, 60, 90, 150, -70]) {
      const a = (degrees * Math.PI) / 180;
      const to = [from[0] + 80 * Math.cos(a), from[1] - 80 * Math.sin(a)];
      const tangent = tangentDragVector(state, from, to, anchor, normal);
      assert.ok(tangent, `drag at ${degrees}°: a tangent vector`);
      assert.ok(Math.abs(tangent[1]) < 1e-12 * Math.hypot(...tangent), 'in the tangent plane');
      const end = toPixels(camera, unit(tangent).map((x) => 1e-4 * x));
      const seen = [end[0] - from[0], end[1] - from[1]];
      assert.ok(Math.abs(screenAngle(seen) - degrees) < 1e-4, `drag at ${degrees}°, seen at ${screenAngle(seen)}°`);

      const field = session.directionField({ type: 'screen', from, to, camera: { ...state, anchor, normal } });
      const core = [field[0], field[1], field[2]];
      const agreement = unit(core).reduce((sum, x, k) => sum + x * unit(tangent)[k], 0);
      assert.ok(agreement > 1 - 1e-6, `drag at ${degrees}°: the core's direction ${core} and the JS one ${tangent} agree`);
    }
  });
}

test('a plane seen edge-on has no tangent drag: the caller falls back to the image-plane drag', () => {
  const { state } = cameraAt([0, 0, 5]);
  assert.equal(tangentDragVector(state, [450, 300], [450, 250], [0, 0, 0], [0, 1, 0]), null);
});
