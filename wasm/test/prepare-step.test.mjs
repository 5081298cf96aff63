// The background preparation through the module (Session.prepareStep), as
// the solver worker runs it after a load or a commit: a part per call, so a
// select asked for meanwhile runs between two parts. The edit after it
// factorizes nothing more and gives the same positions, bit for bit, as an
// edit on a session that was never prepared.
import assert from 'node:assert/strict';
import { before, test } from 'node:test';

import { loadAnisoform, sessionWith } from '../node-support.mjs';

let wasm;
before(async () => {
  ({ wasm } = await loadAnisoform());
});

const FILE = 'closed/cat-low-resolution.obj';
const LEGS = (lowY, height) => ({ box: { min: [-1e9, -1e9, -1e9], max: [1e9, lowY + 0.3 * height, 1e9] } });
const STRETCH = { method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: 1.4 }, maxIterations: 6 };

function verticalRange(session) {
  const ys = session.positions().filter((_, i) => i % 3 === 1);
  const low = Math.min(...ys);
  return { low, height: Math.max(...ys) - low };
}

function legStretch(session) {
  const { low, height } = verticalRange(session);
  session.select(LEGS(low, height));
  const result = session.deform(STRETCH);
  return { result, positions: session.positionsExact().slice() };
}

test('prepareStep: parts rising to 1 with a select between them; the edit after is the cold one, bit for bit', () => {
  const cold = sessionWith(wasm, FILE);
  const prepared = sessionWith(wasm, FILE);
  try {
    const expected = legStretch(cold);
    assert.equal(cold.factorizations(), 1);

    const reported = [];
    prepared.setProgress((stage, share) => reported.push([stage, share]));
    const shares = [prepared.prepareStep(), prepared.prepareStep()];
    // A select between two parts answers at once and is kept.
    const { low, height } = verticalRange(prepared);
    const count = prepared.select(LEGS(low, height));
    assert.ok(count > 100, `${count} selected`);
    const selection = prepared.selection().slice();
    while (shares.at(-1) < 1 && shares.length < 10) shares.push(prepared.prepareStep());
    // The copy and Laplacian, the workspace, the ordering, four parts of the
    // numeric factorization, the AnARAP structures, the warm-up.
    assert.equal(shares.length, 9, `shares ${shares}`);
    for (let k = 1; k < shares.length; k++) assert.ok(shares[k] > shares[k - 1], `shares ${shares}`);
    assert.equal(shares.at(-1), 1);
    assert.ok(reported.every(([stage]) => stage === 'factorize'), JSON.stringify(reported));
    assert.equal(prepared.factorizations(), 1);
    assert.deepEqual(prepared.selection(), selection);
    assert.equal(prepared.prepareStep(), 1, 'nothing left');

    const result = prepared.deform(STRETCH);
    assert.equal(result.factorizations, 1, 'the edit factorizes nothing more');
    assert.equal(result.iterations, expected.result.iterations);
    assert.deepEqual(prepared.positionsExact(), expected.positions);
  } finally {
    cold.delete();
    prepared.delete();
  }
});

// The preparation's last part runs a preview's work once and throws it away
// (Deformer::prepare_step: frames, scale targets and steps, an iteration),
// so that a drag's first preview does not pay for it. The previews after it
// must be those of a session never prepared, bit for bit: a slider's values
// (from the scale steps, warm-started from the kept rotations) and a screen
// drag's (its targets made directly).
test('prepareStep: the previews after the preparation are the unprepared ones, bit for bit', () => {
  const IDENTITY = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];
  const previews = [
    { ...STRETCH, maxIterations: 1, warmStart: true, preview: true },
    { ...STRETCH, transform: { scale: 1.5 }, maxIterations: 1, warmStart: true, preview: true },
    { ...STRETCH, maxIterations: 1, warmStart: true, preview: true, direction: { type: 'screen', from: [400, 300], to: [430, 250],
      camera: { view: IDENTITY, projection: IDENTITY, viewport: [0, 0, 800, 600], anchor: [0, 0, 0] } } },
  ];
  const run = (session) => {
    const { low, height } = verticalRange(session);
    session.select(LEGS(low, height));
    return previews.map((op) => {
      session.deform(op);
      return session.positionsExact().slice();
    });
  };
  const cold = sessionWith(wasm, FILE);
  const prepared = sessionWith(wasm, FILE);
  try {
    while (prepared.prepareStep() < 1);
    const expected = run(cold);
    const got = run(prepared);
    assert.notDeepEqual(got[0], got[1], 'the slider moved the mesh');
    got.forEach((positions, k) => assert.deepEqual(positions, expected[k], `preview ${k}`));
  } finally {
    cold.delete();
    prepared.delete();
  }
});

test('prepareStep after a commit prepares the new rest pose; an edit between the parts finishes them, its progress carrying on', () => {
  const session = sessionWith(wasm, FILE);
  try {
    legStretch(session);
    session.commit();
    const before = session.factorizations();
    // The copy and Laplacian, the workspace, the ordering, a quarter of the numeric factorization.
    const shares = [];
    for (let part = 0; part < 4; part++) shares.push(session.prepareStep());
    assert.ok(shares.at(-1) < 1, `shares ${shares}`);
    assert.equal(session.factorizations(), before, 'ordered and analysed, not yet factorized');
    // The edit's set-up progress goes on from the preparation's share on
    // the same scale: the app's "Preparing the solver" fell from 56 % to
    // 35 % when an edit came after the ordering.
    const reported = [];
    session.setProgress((stage, fraction) => reported.push([stage, fraction]));
    const result = session.deform(STRETCH);
    session.setProgress(null);
    const setUp = reported.filter(([stage]) => stage === 'factorize').map(([, fraction]) => fraction);
    assert.ok(setUp.length > 0 && setUp[0] >= shares.at(-1), `after ${shares.at(-1)}: ${setUp}`);
    for (let k = 1; k < setUp.length; k++) assert.ok(setUp[k] >= setUp[k - 1], `set-up progress ${setUp}`);
    assert.equal(setUp.at(-1), 1);
    assert.deepEqual(reported.slice(0, setUp.length).map(([stage]) => stage), setUp.map(() => 'factorize'));
    assert.equal(result.factorizations, before + 1);
    assert.equal(session.prepareStep(), 1, 'the edit built the rest');
    assert.equal(session.factorizations(), before + 1);
  } finally {
    session.delete();
  }
});

test('prepareStep before a mesh is loaded says so', () => {
  const session = new wasm.Session();
  try {
    assert.throws(() => session.prepareStep(), { code: 'bad-parameter', message: /no mesh is loaded/ });
  } finally {
    session.delete();
  }
});
