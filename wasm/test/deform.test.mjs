// The solver properties of METHOD §9 through the WASM session, on real meshes:
// the identity leaves the mesh alone, a global stretch of a plane is exactly
// diag(su, 1, 1), AnARAP's energy decreases, only a new rest pose (or pin
// set) refactors, the twist origin defaults to the selection's centroid line,
// and results count the triangles an edit folded over.
import assert from 'node:assert/strict';
import { before, test } from 'node:test';

import { transformUsesDirection } from '../../web/src/tools/direction-source.js';
import { boundingBox, loadAnisoform, maxVertexDistance, sessionWith } from '../node-support.mjs';

let wasm;
before(async () => {
  ({ wasm } = await loadAnisoform());
});

function withSession(file, body) {
  const session = sessionWith(wasm, file);
  try {
    return body(session);
  } finally {
    session.delete();
  }
}

for (const method of ['anarap', 'andefgrad', 'linear']) {
  test(`${method}: T = I leaves the mesh unchanged`, () => withSession('closed/spool.off', (session) => {
    const rest = session.positions().slice();
    const diagonal = boundingBox(rest).diagonal;
    assert.equal(session.select({ all: true }), session.info().vertices);
    session.deform({ method, direction: { type: 'global', vector: [0, 1, 0] }, transform: {} });
    assert.ok(maxVertexDistance(session.positions(), rest) <= 1e-6 * diagonal);
  }));
}

// Exactly, and without a factorization: the core returns the rest pose
// (Deformer moves_nothing; it used to solve, 1e-14 off, 6.7 s on the koala).
test('an empty selection leaves the mesh unchanged to the bit, without factorizing, as the CLI', () => withSession('closed/spool.off', (session) => {
  const rest = session.positions().slice();
  for (const method of ['anarap', 'andefgrad', 'linear']) {
    const result = session.deform({ method, direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: 1.5 } });
    assert.equal(result.selected, 0);
    assert.deepEqual(session.positions(), rest, method);
    assert.equal(result.factorizations, 0, method);
  }
}));

test('andefgrad: a global stretch of a plane along an in-plane axis gives exactly diag(su, 1, 1) up to translation', () => withSession('open/plane.off', (session) => {
  const rest = session.positions().slice();
  const { diagonal, min, max } = boundingBox(rest);
  const extent = max.map((x, k) => x - min[k]);
  const flat = extent.indexOf(Math.min(...extent));
  assert.ok(extent[flat] < 1e-9 * diagonal, 'plane.off lies in an axis plane');
  const axis = (flat + 1) % 3;  // in the plane
  const vector = [0, 0, 0];
  vector[axis] = 1;
  const su = 1.5;
  const scale = [1, 1, 1];
  scale[axis] = su;
  session.select({ all: true });
  session.deform({ method: 'andefgrad', direction: { type: 'global', vector }, transform: { scale: su } });
  const result = session.positions();
  const n = rest.length / 3;
  const translation = [0, 0, 0];
  for (let i = 0; i < n; ++i) {
    for (let k = 0; k < 3; ++k) translation[k] += (result[3 * i + k] - scale[k] * rest[3 * i + k]) / n;
  }
  const expected = rest.map((x, j) => scale[j % 3] * x + translation[j % 3]);
  assert.ok(maxVertexDistance(result, expected) <= 1e-6 * diagonal);
}));

test('anarap: the energy never increases over the iterations', () => withSession('closed/torus.obj', (session) => {
  const { min, max } = boundingBox(session.positions());
  session.select({ box: { min, max: [max[0], max[1], (min[2] + max[2]) / 2 + 0.3 * (max[2] - min[2])] } }, { falloff: 0.2 });
  const result = session.deform({ method: 'anarap', direction: { type: 'global', vector: [1, 0, 0] }, transform: { scale: 1.4 }, maxIterations: 30, tolerance: 0 });
  assert.equal(result.energyHistory.length, result.iterations);
  assert.ok(result.iterations >= 2);
  for (let k = 1; k < result.energyHistory.length; ++k) {
    const [previous, current] = [result.energyHistory[k - 1], result.energyHistory[k]];
    assert.ok(current <= previous * (1 + 1e-12), `iteration ${k}: ${current} > ${previous}`);
  }
  assert.ok(result.energyHistory.at(-1) < result.energyHistory[0]);
}));

test('a new amount, direction or method never refactors; a new rest pose refactors once', () => withSession('closed/spool.off', (session) => {
  session.select({ sphere: { center: [0, 0.5, 0], radius: 0.5 } }, { falloff: 0.1 });
  const first = session.deform({ method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: 1.2 }, maxIterations: 5 });
  assert.equal(first.factorizations, 1);
  for (const op of [
    { method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: 1.5 }, maxIterations: 5 },
    { method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: 1.7 }, preview: true },
    { method: 'anarap', direction: { type: 'global', vector: [1, 0, 0] }, transform: { scale: [1.2, 0.9] }, maxIterations: 5 },
    { method: 'andefgrad', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: 1.3 } },
    { method: 'andefgrad', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: 1.6 } },
  ]) {
    assert.equal(session.deform(op).factorizations, first.factorizations, JSON.stringify(op));
  }
  assert.equal(session.factorizations(), first.factorizations);
  session.commit();
  const afterCommit = session.deform({ method: 'andefgrad', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: 1.1 } });
  assert.equal(afterCommit.factorizations, first.factorizations + 1);
  session.deform({ method: 'andefgrad', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: 1.2 } });
  assert.equal(session.factorizations(), first.factorizations + 1);
}));

test('preview runs at most 4 warm-started iterations; the final solve converges from there', () => withSession('closed/spool.off', (session) => {
  session.select({ sphere: { center: [0, 0.5, 0], radius: 0.5 } }, { falloff: 0.1 });
  const op = { method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: 1.3 } };
  for (const su of [1.1, 1.2, 1.3]) {
    const preview = session.deform({ ...op, transform: { scale: su }, preview: true });
    assert.ok(preview.iterations <= 4);
  }
  const final = session.deform(op);
  assert.ok(final.iterations >= 1);
}));

test('arap with handles moves the handles by the offset and keeps the pins', () => withSession('closed/spool.off', (session) => {
  const rest = session.positions().slice();
  const n = rest.length / 3;
  const byHeight = [...Array(n).keys()].sort((a, b) => rest[3 * a + 1] - rest[3 * b + 1]);
  const count = Math.max(1, Math.round(0.05 * n));
  const pins = byHeight.slice(0, count);
  const handles = byHeight.slice(n - count);
  const move = [0.25, 0, 0];
  session.deform({ method: 'arap', pins, handles, move, maxIterations: 5 });
  const result = session.positions();
  for (const i of pins) {
    assert.ok(Math.hypot(result[3 * i] - rest[3 * i], result[3 * i + 1] - rest[3 * i + 1], result[3 * i + 2] - rest[3 * i + 2]) < 1e-6);
  }
  for (const i of handles) {
    assert.ok(Math.abs(result[3 * i] - rest[3 * i] - move[0]) < 1e-6);
  }
}));

// Given handles and no pins used to leave every other vertex free: the
// whole mesh followed the handles rigidly, whatever was selected (the CLI's
// --handle without --pin likewise, tests/test_arap_pins.cpp).
test('arap with given handles and no pins holds the unselected vertices; with nothing unselected it is refused', () => withSession('closed/spool.off', (session) => {
  const rest = session.positions().slice();
  const n = rest.length / 3;
  const { min, max } = boundingBox(rest);
  const height = max[1] - min[1];
  const handles = [...Array(n).keys()].filter((i) => rest[3 * i + 1] > max[1] - 0.1 * height);
  const move = [0, 0.1 * height, 0];
  session.select({ box: { min: [min[0] - 1, min[1] + 0.5 * height, min[2] - 1], max: [max[0] + 1, max[1] + 1, max[2] + 1] } });
  const selected = session.selection();
  session.deform({ method: 'arap', handles, move, maxIterations: 5 });
  const result = session.positions();
  let held = 0;
  for (let i = 0; i < n; ++i) {
    if (selected[i] !== 0) continue;
    ++held;
    for (let k = 0; k < 3; ++k) assert.equal(result[3 * i + k], rest[3 * i + k], `vertex ${i} is unselected: held at rest`);
  }
  assert.ok(held > 0);
  // positions() are float32: the offset to their precision.
  for (const i of handles) assert.ok(Math.abs(result[3 * i + 1] - rest[3 * i + 1] - move[1]) < 1e-6 * height);
  session.cancel();
  session.select({ all: true });
  assert.throws(() => session.deform({ method: 'arap', handles, move }),
    (error) => error.code === 'bad-parameter' && /nothing holds it/.test(error.message));
}));

test('directionField gives unit tangent directions: a global x on the plane y = 0 is x everywhere; y and curvature give none and are refused', () => withSession('open/plane.off', (session) => {
  const field = session.directionField({ type: 'global', vector: [2, 0, 0] });
  assert.equal(field.length, session.positions().length);
  for (let i = 0; i < field.length; i += 3) {
    assert.ok(Math.abs(Math.abs(field[i]) - 1) < 1e-6 && Math.abs(field[i + 1]) < 1e-6 && Math.abs(field[i + 2]) < 1e-6);
  }
  assert.throws(() => session.directionField({ type: 'global', vector: [0, 1, 0] }),
    (error) => error.code === 'bad-parameter' && /parallel to the surface normal everywhere/.test(error.message));
  assert.throws(() => session.directionField({ type: 'curvature', which: 'max' }),
    (error) => error.code === 'bad-parameter' && /no principal curvature directions/.test(error.message));
}));

test('distortion: 1 for the identity; area ratio and stretch su after a plane stretch in the plane', () => withSession('open/plane.off', (session) => {
  for (const kind of ['area', 'stretch']) {
    assert.ok(session.distortion(kind).every((value) => Math.abs(value - 1) < 1e-9));
  }
  session.select({ all: true });
  session.deform({ method: 'andefgrad', direction: { type: 'global', vector: [1, 0, 0] }, transform: { scale: 1.5 } });
  assert.ok(session.distortion('area').every((value) => Math.abs(value - 1.5) < 1e-5));
  assert.ok(session.distortion('stretch').every((value) => Math.abs(value - 1.5) < 1e-5));
  session.commit();
  assert.ok(session.distortion('area', 'rest').every((value) => Math.abs(value - 1) < 1e-9));
  assert.ok(session.distortion('area', 'loaded').every((value) => Math.abs(value - 1.5) < 1e-5));
}));

test("an AnARAP twist converges (coupled rotations); rotations 'steps' runs exactly rotationSteps steps, in preview too",
  () => withSession('closed/spool.off', (session) => {
    session.select({ all: true });
    const twist = { method: 'anarap', transform: { twist: { axis: [1, 0, 0], degreesPerUnit: 30 } }, warmStart: false };
    const coupled = session.deform({ ...twist, maxIterations: 400 });
    assert.equal(coupled.converged, true);
    assert.ok(coupled.iterations > 1 && coupled.iterations < 400, `${coupled.iterations} iterations`);
    // A preview caps the iterations, the rotations' scheme as any other.
    assert.equal(session.deform({ ...twist, preview: true }).iterations, 4);
    const steps = { ...twist, rotations: 'steps' };
    assert.equal(session.deform(steps).iterations, 1);
    assert.equal(session.deform({ ...steps, rotationSteps: 3, preview: true }).iterations, 3);
    assert.throws(() => session.deform({ ...twist, rotations: 'spin' }), /op.rotations must be one of coupled, steps/);
  }));

// The twist origin: the default is the selection's centroid line (at its lowest
// point along the axis); an explicit origin is used as given.
test('twist: the default origin is the centroid line at the lowest point; an explicit origin is used', () =>
  withSession('closed/spool.off', (session) => {
    const rest = session.positions().slice();
    const n = rest.length / 3;
    const diagonal = boundingBox(rest).diagonal;
    session.select({ all: true });
    // The spool turns about x; all weights 1, so the centroid is the vertex mean.
    const origin = [Infinity, 0, 0];
    for (let i = 0; i < n; i++) {
      origin[0] = Math.min(origin[0], rest[3 * i]);
      origin[1] += rest[3 * i + 1] / n;
      origin[2] += rest[3 * i + 2] / n;
    }
    const twist = (extra) => ({ method: 'andefgrad', transform: { twist: { axis: [1, 0, 0], degreesPerUnit: 90, ...extra } } });
    session.deform(twist({}));
    const byDefault = session.positions().slice();
    session.deform(twist({ origin }));
    assert.ok(maxVertexDistance(session.positions(), byDefault) <= 1e-5 * diagonal);
    session.deform(twist({ origin: [origin[0], 0.5, 0] }));
    assert.ok(maxVertexDistance(session.positions(), byDefault) > 0.05 * diagonal, 'an origin on the rim moves the part');
  }));

// Every result says how many triangles the edit folded over.
// The app's Apply sends a twist or a rotation about the normal without a
// direction (web/src/tools/direction-source.js): their results must be the
// same for every direction, and every other edit's must not be.
test('the edits the app sends without a direction are exactly those whose result no direction changes', () => {
  const transforms = [
    { twist: { axis: [0, 1, 0], degreesPerUnit: 60 } },
    { rotate: { axis: 'n', degrees: 30 } },
    { rotate: { axis: 'u', degrees: 30 } },
    { rotate: { axis: 'v', degrees: 30 } },
    { scale: [1.4, 1] },
    { scale: [1, 1.3] },
    { shear: 0.3 },
    { twist: { axis: [0, 1, 0], degreesPerUnit: 60 }, scale: [1.2, 1] },
  ];
  const solve = (method, transform, direction) => withSession('closed/spot_triangulated.obj', (session) => {
    const { min, max } = boundingBox(session.positions());
    session.select({ box: { min: [min[0], 0.5 * (min[1] + max[1]), min[2]], max } });
    session.deform({ method, transform, ...(direction && { direction }) });
    return session.positions().slice();
  });
  for (const method of ['anarap', 'andefgrad', 'linear']) {
    for (const transform of transforms) {
      const alongX = solve(method, transform, { type: 'global', vector: [1, 0, 0] });
      const others = [solve(method, transform, { type: 'global', vector: [0, 0, 1] }), solve(method, transform, null)];
      const differences = others.map((positions) => maxVertexDistance(positions, alongX));
      const label = `${method} ${JSON.stringify(transform)}`;
      if (transformUsesDirection(transform)) {
        for (const difference of differences) assert.ok(difference > 1e-3, `${label}: ${difference}`);
      } else {
        assert.deepEqual(differences, [0, 0], label);
      }
    }
  }
});

test('deform results count folded-over triangles', () => withSession('closed/spool.off', (session) => {
  session.select({ all: true });
  const stretched = session.deform({ method: 'andefgrad', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: 1.5 } });
  assert.equal(stretched.inverted, 0);
  const extreme = session.deform({ method: 'andefgrad', transform: { twist: { axis: [1, 0, 0], degreesPerUnit: 20000 } } });  // near the largest valid twist on the spool (limits.h)
  assert.ok(Number.isInteger(extreme.inverted) && extreme.inverted > 0, `inverted ${extreme.inverted}`);
}));
