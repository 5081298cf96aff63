// Errors reach JS as AnisoformError with a code and a message naming the
// field or element at fault, and the module keeps working after any number
// of them. What the module refuses at the JS boundary (docs/ROBUSTNESS.md):
// indices that are not integers in range (checked before C++ narrows them, so
// 2**32 + 1 cannot wrap to vertex 1), direction amounts outside the rule of
// the global scale, unbounded curvature smoothing; and running out of memory,
// reported as 'out-of-memory' with everything the failed call took freed.
import assert from 'node:assert/strict';
import { before, test } from 'node:test';

import { loadAnisoform, sessionWith } from '../node-support.mjs';

let wasm;
let benchWasm; // the same Session plus cappedCylinder, which can fill the memory from inside
let AnisoformError;
before(async () => {
  ({ wasm, AnisoformError } = await loadAnisoform());
  ({ wasm: benchWasm } = await loadAnisoform({ bench: true }));
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

// plane.off: 841 vertices in y = 0, so y is its normal and x a tangent.
function withPlane(body, module = wasm) {
  const session = sessionWith(module, 'open/plane.off');
  try {
    body(session);
  } finally {
    session.delete();
  }
}

test('direction constraint amounts su/sv <= 0 are refused like a global scale <= 0', () => {
  withPlane((session) => {
    const arrows = (amounts) => ({ type: 'constraints', constraints: [{ vertex: 0, direction: [1, 0, 0], ...amounts }] });
    for (const [amounts, message] of [
      [{ su: 0 }, /direction constraint 1 \(vertex 0\): su must be positive, got 0/],
      [{ su: -1 }, /direction constraint 1 \(vertex 0\): su must be positive, got -1/],
      [{ su: 1.2, sv: 0 }, /direction constraint 1 \(vertex 0\): sv must be positive, got 0/],
    ]) {
      expectError(() => session.deform({ method: 'andefgrad', direction: arrows(amounts) }), 'bad-parameter', message);
      expectError(() => session.directionField(arrows(amounts)), 'bad-parameter', message);
      expectError(() => session.flatten({ direction: arrows(amounts) }), 'bad-parameter', message);
    }
    expectError(() => session.deform({ transform: { scale: -1 } }), 'bad-parameter', /scale su must be positive, got -1/);
  });
});

test('vertex indices are refused unless integers in range, naming the value as given', () => {
  withPlane((session) => {
    const selected = session.select({ vertices: [3, 4] });
    const refused = [
      [2 ** 32 + 1, /must be an integer from 0 to 2147483647, got 4294967297/],
      [1e10, /got 10000000000/],
      [2 ** 31, /got 2147483648/],
      [1.5, /got 1\.5/],
      [-1, /got -1/],
      [NaN, /must be a number, got 'NaN'/],
    ];
    for (const [index, message] of refused) {
      expectError(() => session.select({ vertices: [0, index] }), 'bad-parameter', /region\.vertices element 1 /);
      expectError(() => session.select({ vertices: [index] }), 'bad-parameter', message);
      expectError(() => session.select({ vertices: Float64Array.of(index) }), 'bad-parameter', message);
      expectError(() => session.deform({ pins: [index] }), 'bad-parameter', message);
      expectError(() => session.deform({ method: 'arap', handles: [index] }), 'bad-parameter', message);
    }
    // Non-numbers are not converted (a bulk copy would read null as vertex 0).
    expectError(() => session.select({ vertices: [null] }), 'bad-parameter', /region\.vertices element 0 must be a number, got null/);
    expectError(() => session.select({ vertices: ['3'] }), 'bad-parameter', /must be a number, got '3'/);
    // A constraint's vertex goes through the same narrowing.
    expectError(() => session.deform({ direction: { type: 'constraints', constraints: [{ vertex: 2 ** 32 + 1, direction: [1, 0, 0] }] } }),
      'bad-parameter', /op\.direction\.constraints\[0\]\.vertex must be an integer >= 0, got 4294967297/);
    // In range for a 32-bit index but not a vertex of this mesh: the core's check.
    expectError(() => session.select({ vertices: [841] }), 'bad-parameter', /selected vertex 841 is out of range \(the mesh has 841 vertices\)/);
    // Nothing was selected by any of these.
    assert.equal(session.select({ vertices: [] }, { mode: 'add' }), selected);
    assert.deepEqual(Array.from(session.selection()).flatMap((w, i) => (w > 0 ? [i] : [])), [3, 4]);
  });
});

test('setMesh triangle corners are checked before they become uint32', () => {
  const session = new wasm.Session();
  try {
    const positions = [0, 0, 0, 1, 0, 0, 0, 1, 0];
    expectError(() => session.setMesh(positions, [0, 1, 2 ** 32 + 2]), 'bad-parameter', /setMesh: triangles element 2 must be an integer from 0 to 4294967295, got 4294967298/);
    expectError(() => session.setMesh(positions, [0, 1, -1]), 'bad-parameter', /got -1/);
    assert.equal(session.setMesh(positions, Uint32Array.of(0, 1, 2)).triangles, 1);
  } finally {
    session.delete();
  }
});

test('curvature smoothing is bounded to 0..1000 steps', () => {
  withPlane((session) => {
    const curvature = (smoothing) => ({ type: 'curvature', which: 'min', smoothing });
    // 1e9 steps once ran for 12+ minutes inside one call.
    expectError(() => session.deform({ method: 'andefgrad', direction: curvature(1e9) }), 'bad-parameter', /smoothing steps must be an integer from 0 to 1000, got 1000000000/);
    expectError(() => session.directionField(curvature(1001)), 'bad-parameter', /from 0 to 1000, got 1001/);
    // 1000 is within the bound: the call gets as far as the plane's flatness, which gives no direction.
    expectError(() => session.directionField(curvature(1000)), 'bad-parameter', /the surface has no principal curvature directions/);
  });
});

test('out of memory is its own code, names the limit, and leaves the session and the heap as they were', () => {
  withPlane((session) => {
    const before = benchWasm.memoryUse();
    assert.equal(before.limit, 2 ** 31);
    // Files as large as the module's whole memory: their copy into the module
    // fails (malloc returns null; beyond 2**31 - 1 bytes std::vector refuses).
    for (const size of [2 ** 31 - 4096, 2 ** 31 + 16]) {
      const huge = new Uint8Array(size);
      for (let attempt = 0; attempt < 2; ++attempt) {
        expectError(() => session.loadMesh(huge, 'huge.off'), 'out-of-memory', /out of memory: .*more than the 2 GB of memory the module may use/);
      }
    }
    const after = benchWasm.memoryUse();
    assert.equal(after.inUse, before.inUse);
    assert.equal(after.heap, before.heap);
    // Failing half-way: ~30M vertices fill the memory up to its limit (about
    // 4 s) before one allocation fails; unwinding frees every byte taken.
    expectError(() => benchWasm.cappedCylinder(30_000_000), 'out-of-memory', /2 GB/);
    const afterCylinder = benchWasm.memoryUse();
    assert.ok(afterCylinder.heap > 2 ** 30, `the memory grew to ${afterCylinder.heap} bytes first`);
    assert.equal(afterCylinder.inUse, before.inUse);
    assert.equal(session.info().vertices, 841);
    assert.equal(session.select({ all: true }), 841);
    session.deform({ method: 'andefgrad', direction: { type: 'global', vector: [1, 0, 0] }, transform: { scale: 1.2 } });
  }, benchWasm);
});

test('arguments of the wrong type are refused naming the call and the element', () => {
  // Strings were read as numbers, null as 0; embind's own refusal named no call.
  const session = sessionWith(wasm, 'open/plane.off');
  try {
    const P = [0, 0, 0, 1, 0, 0, 0, 1, 0];
    expectError(() => session.setMesh(['0', ...P.slice(1)], [0, 1, 2]), 'bad-parameter', /^setMesh: positions\[0\] is "0", not a number$/);
    expectError(() => session.setMesh([null, ...P.slice(1)], [0, 1, 2]), 'bad-parameter', /^setMesh: positions\[0\] is null, not a number$/);
    expectError(() => session.setMesh(P, new BigUint64Array([0n, 1n, 2n])), 'bad-parameter', /^setMesh: triangles must hold numbers, not BigInts/);
    expectError(() => session.exportMesh(null), 'bad-parameter', /^Session\.exportMesh\(\): an argument has the wrong type: Cannot pass non-string/);
    expectError(() => session.distortion(0), 'bad-parameter', /^Session\.distortion\(\): an argument has the wrong type/);
    assert.equal(session.setMesh(P, [0, 1, 2]).vertices, 3);
  } finally {
    session.delete();
  }
});
