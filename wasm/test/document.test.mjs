// The edit document through the WASM module: a document recorded the way the
// page records it (Session.resolveOp on the rest pose, regions as select
// steps) replays bitwise-equal in two fresh Node sessions, and equal to the
// native CLI's `anisoform replay` within 1e-9 of the bounding-box diagonal
// (the CLI writes OBJ coordinates with 17 significant digits, so the file
// holds its doubles exactly). A bad document is refused naming the op or
// field, and the session keeps its positions.
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { copyFileSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { after, before, test } from 'node:test';

import { boundingBox, loadAnisoform, maxVertexDistance, meshPath, objVertices, sessionWith } from '../node-support.mjs';

const cli = process.env.ANISO_CLI;
const MESH = 'closed/spool.off';

let wasm;
let outputDir;
let documentOfSpool;
before(async () => {
  ({ wasm } = await loadAnisoform());
  outputDir = mkdtempSync(path.join(tmpdir(), 'anisoform-document-'));
  documentOfSpool = recordDocument();
});
after(() => {
  if (outputDir) rmSync(outputDir, { recursive: true, force: true });
});

const REGIONS = [
  { name: 'top', steps: [{ region: { box: { min: [-1, 0.2, -1], max: [1, 1, 1] } }, falloff: 0.1 }] },
  { name: 'middle', steps: [{ region: { sphere: { center: [0, 0, 0], radius: 0.35 } } },
    { region: { sphere: { center: [0, 0.1, 0], radius: 0.1 } }, mode: 'subtract' }] },
  { name: 'everything', steps: [{ region: { all: true } }] },
];
const OPS = [
  { id: 'stretch', region: 'top', op: { direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: 1.3 } } },
  { id: 'twist', region: 'middle', op: { transform: { twist: { axis: [0, 1, 0], degreesPerUnit: 40 } }, rotationSteps: 2 } },
  { id: 'thicken', region: 'everything', op: { method: 'andefgrad', transform: { scale: [1, 1.2] } } },
];

// A region's select steps, from an empty selection, as the page runs them.
function selectRegion(session, rule) {
  session.setSelection(new Float32Array(session.info().vertices));
  for (const step of rule.steps) session.select(step.region, { falloff: step.falloff, mode: step.mode });
}

// As the page does: select, resolve the op on the rest pose, solve, commit.
function recordDocument() {
  const session = sessionWith(wasm, MESH);
  try {
    const ops = OPS.map(({ id, region, op }) => {
      selectRegion(session, REGIONS.find((r) => r.name === region));
      const resolved = session.resolveOp(op);
      session.deform(resolved);
      session.commit();
      return { id, label: id, enabled: true, region, op: resolved };
    });
    const info = session.info();
    return {
      format: 'anisoform-document',
      version: 1,
      mesh: { name: 'spool.off', vertices: info.vertices, triangles: info.triangles, hash: session.meshHash() },
      regions: REGIONS,
      ops,
    };
  } finally {
    session.delete();
  }
}

function replayedInNode(document) {
  const session = sessionWith(wasm, MESH);
  try {
    const summary = session.replay(document);
    assert.equal(summary.replayed, document.ops.filter((o) => o.enabled !== false).length);
    assert.equal(summary.skipped, document.ops.filter((o) => o.enabled === false).length);
    assert.equal(typeof summary.last.iterations, 'number');
    return session.positionsExact();
  } finally {
    session.delete();
  }
}

const bitwiseEqual = (a, b) => a.length === b.length
  && Buffer.compare(Buffer.from(a.buffer, a.byteOffset, a.byteLength), Buffer.from(b.buffer, b.byteOffset, b.byteLength)) === 0;

test('a resolved op is view-independent and a replay is bitwise repeatable', () => {
  const { ops } = documentOfSpool;
  assert.equal(ops[1].op.transform.twist.origin, undefined, "the twist origin is the region's, worked out by replay");
  assert.equal(ops[0].op.preview, false);
  assert.equal(ops[0].op.warmStart, false);
  const first = replayedInNode(documentOfSpool);
  const second = replayedInNode(JSON.parse(JSON.stringify(documentOfSpool)));
  assert.ok(bitwiseEqual(first, second), 'two replays in fresh sessions are bitwise equal');
  const toggled = structuredClone(documentOfSpool);
  toggled.ops[2].enabled = false;
  assert.ok(!bitwiseEqual(replayedInNode(toggled), first), 'a disabled op is skipped');
});

test('Node replay equals `anisoform replay` within 1e-9 of the bbox diagonal', { skip: cli ? false : 'ANISO_CLI is not set' }, (t) => {
  const docPath = path.join(outputDir, 'spool.anisoform.json');
  writeFileSync(docPath, JSON.stringify(documentOfSpool));
  copyFileSync(meshPath(MESH), path.join(outputDir, 'spool.off'));  // the CLI's default: mesh.name beside DOC
  const out = path.join(outputDir, 'replayed.obj');
  const result = JSON.parse(execFileSync(cli, ['replay', docPath, out], { encoding: 'utf8' }));
  assert.equal(result.hash, documentOfSpool.mesh.hash, 'the CLI hashes the mesh as the module does');
  assert.equal(result.replayed, 3);
  const native = objVertices(readFileSync(out, 'utf8'));
  const node = replayedInNode(documentOfSpool);
  const diagonal = boundingBox(node).diagonal;
  const difference = maxVertexDistance(native, node) / diagonal;
  t.diagnostic(`max |Node - CLI| / diagonal = ${difference.toExponential(3)}`);
  assert.ok(difference <= 1e-9, `relative difference ${difference}`);
});

test('a bad document names the op or field and leaves the session as it was', async () => {
  const { AnisoformError } = await loadAnisoform();
  const session = sessionWith(wasm, MESH);
  try {
    session.select({ all: true });
    session.deform({ transform: { scale: 1.1 } });  // an edit in progress
    const before = session.positionsExact();
    const refusals = [
      [{ ...documentOfSpool, version: 2 }, 'bad-parameter', /document\.version is 2, which this build does not read/],
      [{ ...documentOfSpool, ops: [{ ...documentOfSpool.ops[0], region: 'handle' }] }, 'bad-parameter',
        /document\.ops\[0\] \(id 'stretch'\)\.region names region 'handle'/],
      [{ ...documentOfSpool, ops: [{ ...documentOfSpool.ops[0], op: { transform: { scale: 0 } } }] }, 'bad-parameter',
        /document\.ops\[0\] \(id 'stretch'\)\.op\.transform/],
      [{ ...documentOfSpool, mesh: { ...documentOfSpool.mesh, hash: 'fnv1a64:0000000000000000' } }, 'bad-mesh',
        /document mesh hash fnv1a64:0000000000000000 .* does not match the loaded mesh fnv1a64:/],
      [JSON.stringify(documentOfSpool).slice(0, 100), 'bad-parameter', /the document is not valid JSON/],
    ];
    for (const [document, code, message] of refusals) {
      assert.throws(() => session.replay(document), (error) => error instanceof AnisoformError
        && error.code === code && message.test(error.message), String(message));
      assert.ok(bitwiseEqual(session.positionsExact(), before), `positions unchanged after ${message}`);
    }
  } finally {
    session.delete();
  }
});

test("a replay's factorizations and iterations are the session's progress (its scratch session's load is not)", () => {
  const session = sessionWith(wasm, MESH);
  try {
    const calls = [];
    session.setProgress((stage, fraction) => calls.push([stage, fraction]));
    session.replay(documentOfSpool);
    assert.deepEqual([...new Set(calls.map(([stage]) => stage))].sort(), ['factorize', 'solve']);
    // Each of the three ops ends its solve at 1.
    assert.ok(calls.filter(([stage, fraction]) => stage === 'solve' && fraction === 1).length >= 3, JSON.stringify(calls));
    assert.deepEqual(calls.at(-1), ['solve', 1]);
  } finally {
    session.delete();
  }
});

// Every kind of op and region the page records (its API and tools go through
// Session.resolveOp as here), written as the core resolves them.
const VARIED_REGIONS = [
  ...REGIONS,
  { name: 'painted', steps: [{ region: { vertices: [0, 1, 2, 3, 40], weights: [1, 1, 0.5, 0.25, 1] } }] },
];
const VARIED_OPS = [
  ...OPS,
  { id: 'drag', region: 'top', op: { method: 'arap', move: [0.05, 0.1, 0] } },
  { id: 'curvature-shear', region: 'middle', op: { direction: { type: 'curvature', which: 'max', smoothing: 3 },
    transform: { shear: 0.2 } } },
  { id: 'field-rotate', region: 'middle', op: { direction: { type: 'constraints', constraints: [
    { vertex: 5, direction: [1, 0, 0] }, { vertex: 60, direction: [0, 0, 1] }] },
  transform: { rotate: { axis: 'n', degrees: 15 } }, rotations: 'steps', rotationSteps: 3, acceleration: 'anderson' } },
  { id: 'linear', region: 'painted', op: { method: 'linear', direction: { type: 'global', vector: [0, 0, 1] },
    transform: { thickness: 1.1 }, maxIterations: 10000 } },
];

test('documents the core writes pass docs/document.schema.json, whose iteration bounds are the core\'s', async () => {
  const { schemaErrors } = await import('../../docs/document-schema.mjs');
  const session = sessionWith(wasm, MESH);
  try {
    const ops = VARIED_OPS.map(({ id, region, op }) => {
      selectRegion(session, VARIED_REGIONS.find((r) => r.name === region));
      return { id, label: id, enabled: true, region, op: session.resolveOp(op) };
    });
    const info = session.info();
    const document = {
      format: 'anisoform-document',
      version: 1,
      mesh: { name: 'spool.off', vertices: info.vertices, triangles: info.triangles, hash: session.meshHash() },
      regions: VARIED_REGIONS,
      ops,
    };
    assert.deepEqual(ops.map((entry) => entry.op.acceleration), ['lbfgs', 'lbfgs', 'lbfgs', 'lbfgs', 'lbfgs', 'anderson', 'lbfgs']);
    assert.deepEqual(schemaErrors(document), []);
    assert.deepEqual(schemaErrors(documentOfSpool), []);
    assert.equal(session.replay(document).replayed, VARIED_OPS.length);

    // One past the bound: the schema and the core both refuse it, by name.
    for (const key of ['maxIterations', 'rotationSteps']) {
      const over = structuredClone(document);
      over.ops[0].op[key] = 10001;
      assert.ok(schemaErrors(over).some((line) => line.startsWith(`/ops/0/op/${key}: must be <= 10000`)), key);
      assert.throws(() => session.replay(over), new RegExp(`op\\.${key} must be an integer from 1 to 10000, got 10001`));
    }
  } finally {
    session.delete();
  }
});

test('a curvature field without clear directions is warned about in the result and the replay summary the page shows', () => {
  // A hemisphere's "min curvature" follows its triangulation: 90 % of its
  // vertices have no clear principal direction. It was edited silently.
  const session = sessionWith(wasm, 'open/hemisphere.obj');
  try {
    session.select({ all: true });
    const op = { method: 'andefgrad', direction: { type: 'curvature', which: 'min' }, transform: { scale: 1.3 } };
    const result = session.deform(op);
    assert.equal(result.warnings.length, 1);
    assert.match(result.warnings[0], /^90 % of the selected vertices \(\d+ of 2051\) have no clear principal curvature direction/);
    session.cancel();
    const info = session.info();
    const summary = session.replay({
      format: 'anisoform-document', version: 1,
      mesh: { name: 'hemisphere.obj', vertices: info.vertices, triangles: info.triangles, hash: session.meshHash() },
      regions: [{ name: 'all', steps: [{ region: { all: true } }] }],
      ops: [{ id: 'along', label: 'along', enabled: true, region: 'all', op: session.resolveOp(op) }],
    });
    assert.deepEqual(summary.warnings, [`document.ops[0] (id 'along'): ${result.warnings[0]}`]);
    // A tube's field is clear: nothing to say.
    const knot = sessionWith(wasm, 'closed/knot1.off');
    knot.select({ all: true });
    assert.deepEqual(knot.deform(op).warnings, []);
    knot.delete();
  } finally {
    session.delete();
  }
});
