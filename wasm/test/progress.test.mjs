// Progress of the long calls (Session.setProgress): each stage in order, its
// fractions rising to 1, reported from inside the call.
import assert from 'node:assert/strict';
import { before, test } from 'node:test';

import { loadAnisoform, meshBytes } from '../node-support.mjs';

let wasm;
let AnisoformError;
before(async () => {
  ({ wasm, AnisoformError } = await loadAnisoform());
});

const fractionsOf = (calls, stage) => calls.filter(([name]) => name === stage).map(([, fraction]) => fraction);

function assertRisingToOne(fractions, what) {
  assert.ok(fractions.length >= 2, `${what}: ${JSON.stringify(fractions)}`);
  for (let i = 1; i < fractions.length; i++) assert.ok(fractions[i] >= fractions[i - 1], `${what} fell: ${fractions}`);
  assert.ok(fractions.every((fraction) => fraction >= 0 && fraction <= 1), `${what}: ${fractions}`);
  assert.equal(fractions.at(-1), 1, what);
}

test('a load, a committed AnARAP stretch and a flatten report their stages with fractions rising to 1', () => {
  const session = new wasm.Session();
  try {
    const calls = [];
    session.setProgress((stage, fraction) => calls.push([stage, fraction]));

    session.loadMesh(meshBytes('closed/armadillo.off'), 'armadillo.off');
    assert.deepEqual(calls.map(([stage]) => stage), ['load', 'load', 'load', 'load']);
    assert.deepEqual(fractionsOf(calls, 'load'), [0, 0.05, 0.35, 1]);

    calls.length = 0;
    const ys = session.positions().filter((_, i) => i % 3 === 1);
    const cut = Math.max(...ys) - (Math.max(...ys) - Math.min(...ys)) / 3;
    assert.ok(session.select({ box: { min: [-1e9, cut, -1e9], max: [1e9, 1e9, 1e9] } }) > 1000);
    const stretch = { method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: 1.2 }, maxIterations: 8, tolerance: 0 };
    const result = session.deform(stretch);
    // The set-up first, on the background preparation's scale (core
    // progress.h): the unit copy and its Laplacian (0.3), the workspace
    // (0.35), the factorization from 0.35 (its ordering and analysis a
    // 0.35 share of its 0.6), by twentieths of its numeric work, to 0.95,
    // and the iterations' structures (1); then one report per iteration
    // (k of 8) and 1 at the end.
    const factorize = fractionsOf(calls, 'factorize');
    assert.deepEqual(factorize.slice(0, 3), [0.3, 0.35, 0.35]);
    assert.ok(Math.abs(factorize[3] - (0.35 + 0.6 * 0.35)) < 1e-12, `factorize: ${factorize}`);
    assert.ok(factorize.length >= 11, `factorize: ${factorize}`);
    for (let i = 3; i < factorize.length; i++) assert.ok(factorize[i] > factorize[i - 1], `factorize: ${factorize}`);
    assert.deepEqual(factorize.slice(-2), [0.95, 1]);
    assert.deepEqual(calls.slice(0, factorize.length).map(([stage]) => stage), factorize.map(() => 'factorize'));
    const solve = fractionsOf(calls, 'solve');
    assert.equal(result.iterations, 8);
    assert.deepEqual(solve, [1, 2, 3, 4, 5, 6, 7, 8].map((k) => k / 8).concat([1]));

    // The same rest pose and pins again: no new factorization.
    calls.length = 0;
    session.deform({ ...stretch, maxIterations: 3 });
    session.commit();
    assert.deepEqual(fractionsOf(calls, 'factorize'), []);
    assertRisingToOne(fractionsOf(calls, 'solve'), 'second solve');

    calls.length = 0;
    session.loadMesh(meshBytes('open/hemisphere.obj'), 'hemisphere.obj');
    calls.length = 0;
    session.flatten({ compress: [0.8, 1] });
    assertRisingToOne(fractionsOf(calls, 'flatten'), 'flatten');

    calls.length = 0;
    session.setProgress(null);
    session.flatten({ compress: [0.9, 1] });
    assert.deepEqual(calls, []);
    assert.throws(() => session.setProgress('not a function'), (error) => error instanceof AnisoformError && error.code === 'bad-parameter');
  } finally {
    session.delete();
  }
});

test('a Session call from inside a progress report is refused, and the module keeps working', () => {
  // A setMesh or delete from there freed memory the running flatten/deform
  // used: "memory access out of bounds", then every session of the module failed.
  const plane = meshBytes('open/plane.off');
  const session = new wasm.Session();
  const other = new wasm.Session();
  try {
    session.loadMesh(plane, 'plane.off');
    session.select({ all: true });
    for (const [name, inside] of [
      ['setMesh', () => session.setMesh([0, 0, 0, 1, 0, 0, 0, 1, 0], [0, 1, 2])],
      ['delete', () => session.delete()],
      ['loadMesh', () => other.loadMesh(plane, 'plane.off')],
    ]) {
      let refusal = null;
      session.setProgress(() => {
        if (refusal) return;
        try {
          inside();
          refusal = 'none';
        } catch (error) {
          refusal = error;
        }
      });
      const result = session.flatten({});
      assert.ok(result.metrics.triangles > 0, name);
      assert.ok(refusal instanceof AnisoformError, `${name}: ${refusal}`);
      assert.equal(refusal.code, 'bad-parameter');
      assert.match(refusal.message, new RegExp(`^Session\\.${name}\\(\\) was called while Session\\.flatten\\(\\) runs`));
      assert.equal(session.isDeleted(), false);
    }
    // A report that throws: the call runs to its end, then says so.
    session.setProgress(() => {
      throw new Error('report broke');
    });
    assert.throws(() => session.deform({ transform: { scale: 1.2 } }),
      (error) => error.code === 'bad-parameter' && /^Session\.deform\(\) has run to its end, but its progress report threw: report broke$/.test(error.message));
    session.setProgress(null);
    const fresh = new wasm.Session();
    fresh.loadMesh(plane, 'plane.off');
    fresh.select({ all: true });
    assert.ok(fresh.deform({ transform: { scale: 1.2 } }).iterations > 0);
    fresh.delete();
  } finally {
    session.delete();
    other.delete();
  }
});
