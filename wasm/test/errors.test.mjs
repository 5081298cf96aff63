// Errors reach JS as AnisoformError with a code and a message naming the
// field or element at fault, and the module keeps working after any number
// of them.
import assert from 'node:assert/strict';
import { before, test } from 'node:test';

import { loadAnisoform, sessionWith } from '../node-support.mjs';

let wasm;
let AnisoformError;
before(async () => {
  ({ wasm, AnisoformError } = await loadAnisoform());
});

function expectError(call, code, pattern) {
  assert.throws(call, (error) => {
    assert.ok(error instanceof AnisoformError, String(error));
    assert.equal(error.name, 'AnisoformError');
    assert.equal(error.code, code, error.message);
    assert.match(error.message, pattern);
    return true;
  });
}

test('op checks name the field at fault', () => {
  const session = sessionWith(wasm, 'open/plane.off');
  try {
    expectError(() => session.deform({ method: 'rigid' }), 'bad-parameter', /op\.method must be one of anarap, andefgrad, arap, linear, got 'rigid'/);
    expectError(() => session.deform({ directon: {} }), 'bad-parameter', /unknown field 'directon'/);
    expectError(() => session.deform({ direction: { type: 'global', vector: [0, 0, 0] } }), 'bad-parameter', /op\.direction\.vector must not be the zero vector/);
    expectError(() => session.deform({ direction: { type: 'global', vector: [1, NaN, 0] } }), 'bad-parameter', /op\.direction\.vector\[1\] must be a finite number/);
    expectError(() => session.deform({ transform: { scale: '2' } }), 'bad-parameter', /op\.transform\.scale/);
    expectError(() => session.deform({ transform: { rotate: { axis: 'x', degrees: 10 } } }), 'bad-parameter', /op\.transform\.rotate\.axis/);
    expectError(() => session.deform({ maxIterations: 0 }), 'bad-parameter', /op\.maxIterations must be an integer >= 1/);
    expectError(() => session.deform({ direction: { type: 'screen', from: [0, 0], to: [1, 1], camera: {} } }), 'bad-parameter', /op\.direction\.camera\.view/);
    expectError(() => session.select({ sphere: { center: [0, 0, 0], radius: 1 }, box: {} }), 'bad-parameter', /exactly one of/);
    expectError(() => session.select({ all: true }, { mode: 'xor' }), 'bad-parameter', /options\.mode/);
    expectError(() => session.exportMesh('glb'), 'bad-parameter', /exportMesh: format/);
    expectError(() => session.distortion('volume'), 'bad-parameter', /distortion: kind/);
  } finally {
    session.delete();
  }
});

test('core errors keep their code and the core message', () => {
  // plane.off lies in y = 0, so y is its normal.
  const session = sessionWith(wasm, 'open/plane.off');
  try {
    expectError(() => session.deform({ transform: { scale: 0 } }), 'bad-parameter', /positive/);
    expectError(() => session.select({ vertices: [841] }), 'bad-parameter', /841/);
    expectError(() => session.deform({ pins: [5000] }), 'bad-parameter', /5000/);
    expectError(() => session.deform({ direction: { type: 'constraints', constraints: [{ vertex: 0, direction: [0, 1, 0] }] } }), 'bad-parameter', /vertex 0/);
    expectError(() => session.loadMesh(new Uint8Array([1, 2, 3]), 'mesh.xyz'), 'bad-parameter', /\.xyz/);
  } finally {
    session.delete();
  }
});

test('the module keeps working, without leaking, after many errors', () => {
  const session = sessionWith(wasm, 'open/plane.off');
  try {
    for (let i = 0; i < 5000; ++i) {
      assert.throws(() => session.loadMesh(new Uint8Array(8), 'bad.ply'), AnisoformError);
      assert.throws(() => session.select({ sphere: { center: [0, 0, 0], radius: -1 } }), AnisoformError);
    }
    assert.equal(session.info().vertices, 841);
    assert.equal(session.select({ all: true }), 841);
    session.deform({ method: 'andefgrad', direction: { type: 'global', vector: [1, 0, 0] }, transform: { scale: 1.2 } });
  } finally {
    session.delete();
  }
});
