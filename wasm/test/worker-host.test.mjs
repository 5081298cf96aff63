// What the page asks the solver worker (web/src/worker/session-host.js) for
// selection and distortion: the core's numbers, passed on unchanged.
import assert from 'node:assert/strict';
import { before, test } from 'node:test';

import { SessionHost } from '../../web/src/worker/session-host.js';
import { Request } from '../../web/src/worker/protocol.js';
import { boundingBox, loadAnisoform, meshBytes } from '../node-support.mjs';

let wasm;
before(async () => {
  ({ wasm } = await loadAnisoform());
});

function hostWith(relative) {
  const host = new SessionHost(wasm, () => {});
  const bytes = meshBytes(relative);
  const name = relative.split('/').pop();
  const { result } = host.handle(Request.loadFile, { source: bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.length), name });
  return { host, positions: result.positions };
}

test('a buffer loads at once, and its bytes come back as the Blob the autosave keeps', async () => {
  const bytes = meshBytes('closed/spot_triangulated.obj');
  const source = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.length);
  const host = new SessionHost(wasm, () => {});
  try {
    const { result } = host.handle(Request.loadFile, { source, name: 'spot_triangulated.obj' });
    assert.ok(result.sourceBytes instanceof Blob);
    assert.deepEqual(new Uint8Array(await result.sourceBytes.arrayBuffer()), new Uint8Array(bytes));
    assert.equal(result.info.vertices, result.positions.length / 3);
  } finally {
    host.session.delete();
  }
});

test('select answers with the count and a copy of the core selection, combined with the one sent before', () => {
  const { host, positions } = hostWith('closed/spot_triangulated.obj');
  try {
    const { min, max, diagonal } = boundingBox(positions);
    const middle = [0, 1, 2].map((k) => (min[k] + max[k]) / 2);
    const half = new Float32Array(positions.length / 3).fill(0.5);
    host.handle(Request.setSelection, { weights: half });
    const { result } = host.handle(Request.select, {
      region: { sphere: { center: middle, radius: 0.2 * diagonal } },
      options: { falloff: 0.1 * diagonal, mode: 'add' },
    });
    assert.deepEqual(result.weights, host.session.selection().slice());
    assert.equal(result.count, result.weights.length, 'add keeps every 0.5 weight');
    assert.ok(result.weights.some((w) => w === 1) && result.weights.some((w) => w > 0.5 && w < 1));
    assert.ok(result.weights.every((w) => w >= 0.5));
  } finally {
    host.session.delete();
  }
});

test('a deform reply carries the core distortion against the mesh as loaded when asked', () => {
  const { host } = hostWith('closed/spot_triangulated.obj');
  try {
    host.handle(Request.setSelection, { weights: new Float32Array(host.session.info().vertices).fill(1) });
    const op = { method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: [1.5, 1] } };
    const plain = host.handle(Request.deform, { op, commit: true }).result;
    assert.equal(plain.distortion, undefined);
    const { result } = host.handle(Request.deform, { op: { ...op, transform: { scale: [1.2, 1] } }, commit: false, distortion: 'stretch' });
    assert.deepEqual(result.distortion, host.session.distortion('stretch', 'loaded'));
    assert.deepEqual(host.handle(Request.distortion, { distortion: 'area' }).result.values, host.session.distortion('area', 'loaded'));
    // Stretched along y by 1.5 then 1.2 (the preview starts from the committed
    // rest pose): somewhere a line element grew by about 1.8.
    const largest = Math.max(...result.distortion);
    assert.ok(largest > 1.5 && largest < 2.2, `largest stretch ${largest}`);
  } finally {
    host.session.delete();
  }
});

test('simplify answers with a coarser mesh over the rest mesh\'s own vertices (the page\'s drawing in motion)', async () => {
  const { host, positions } = hostWith('closed/armadillo.off');
  try {
    const triangleCount = host.session.triangles().length / 3;
    const { result, transfer } = await host.handle(Request.simplify, { triangles: 6000 });
    assert.equal(transfer.length, 2);
    const { vertices, triangles } = result;
    assert.ok(triangles.length / 3 <= 6000 && triangles.length / 3 >= 4800, `${triangles.length / 3} of ${triangleCount} triangles`);
    assert.equal(new Set(vertices).size, vertices.length, 'each mesh vertex once');
    assert.ok(vertices.every((v) => v < positions.length / 3));
    assert.ok(triangles.every((p) => p < vertices.length));
    // Every proxy triangle is a real one: no zero-area triangle from a collapse.
    for (let t = 0; t < triangles.length; t += 3) {
      const [a, b, c] = [0, 1, 2].map((k) => vertices[triangles[t + k]]);
      assert.ok(a !== b && b !== c && a !== c, `triangle ${t / 3} has distinct corners`);
    }
  } finally {
    host.session.delete();
  }
});
