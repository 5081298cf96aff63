// The session's state across calls: heap views after memory growth, undo-style
// setPositions round trips, commit and cancel, selection modes, export, and
// failed calls leaving everything as it was.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import path from 'node:path';
import { before, test } from 'node:test';

import { boundingBox, loadAnisoform, maxVertexDistance, meshBytes, meshesDir, sessionWith } from '../node-support.mjs';

let wasm;
let AnisoformError;
before(async () => {
  ({ wasm, AnisoformError } = await loadAnisoform());
});

function withSession(file, body) {
  const session = sessionWith(wasm, file);
  try {
    return body(session);
  } finally {
    session.delete();
  }
}

const STRETCH_Y = { method: 'andefgrad', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: 1.4 } };

test('views detach when the memory grows; fetched again they show the same data', () => withSession('closed/spool.off', (session) => {
  const view = session.positions();
  const copy = view.slice();
  const big = sessionWith(wasm, 'large/koala_loop1_200k.ply');  // grows the WASM memory
  try {
    assert.equal(view.length, 0, 'the old view is detached (if not, the memory did not grow and this test proves nothing)');
    const again = session.positions();
    assert.deepEqual(again, copy);
    assert.equal(big.positions().length, 3 * big.info().vertices);
    assert.equal(big.selection().length, big.info().vertices);
    assert.equal(big.triangles().length, 3 * big.info().triangles);
  } finally {
    big.delete();
  }
}));

test('undo-style round trip: setPositions restores earlier positions exactly and makes them the rest', () => withSession('closed/spool.off', (session) => {
  const original = session.positions().slice();
  session.select({ sphere: { center: [0, 0.5, 0], radius: 0.5 } }, { falloff: 0.1 });
  session.deform(STRETCH_Y);
  session.commit();
  const edited = session.positions().slice();
  assert.ok(maxVertexDistance(edited, original) > 0.01, 'the edit moved the mesh');

  session.setPositions(original);  // undo
  assert.deepEqual(session.positions(), original);
  session.setPositions(edited);  // redo
  assert.deepEqual(session.positions(), edited);

  // The restored positions are the rest: the same edit from them equals the
  // same edit from a fresh load of those positions.
  session.setPositions(original);
  session.deform(STRETCH_Y);
  const again = session.positions().slice();
  session.commit();
  assert.ok(maxVertexDistance(again, edited) <= 1e-6 * boundingBox(original).diagonal);
}));

test('cancel goes back to the rest pose; deform always starts from the rest pose', () => withSession('closed/spool.off', (session) => {
  const rest = session.positions().slice();
  session.select({ all: true });
  session.deform({ ...STRETCH_Y, transform: { scale: 1.2 } });
  const once = session.positions().slice();
  session.deform({ ...STRETCH_Y, transform: { scale: 1.2 } });
  assert.deepEqual(session.positions(), once, 'a repeated deform does not compound');
  session.cancel();
  assert.deepEqual(session.positions(), rest);
}));

test('selection modes: replace, add = max, subtract = min(old, 1 - new); setSelection', () => withSession('closed/spool.off', (session) => {
  const n = session.info().vertices;
  const top = session.select({ box: { min: [-1, 0.25, -1], max: [1, 1, 1] } });
  const bottom = session.select({ box: { min: [-1, -1, -1], max: [1, -0.25, 1] } });
  assert.ok(top > 0 && bottom > 0);
  assert.equal(session.select({ box: { min: [-1, 0.25, -1], max: [1, 1, 1] } }, { mode: 'add' }), top + bottom);
  assert.equal(session.select({ box: { min: [-1, 0.25, -1], max: [1, 1, 1] } }, { mode: 'subtract' }), bottom);
  assert.equal(session.select({ all: true }), n);
  assert.equal(session.select({ vertices: [0, 5, 7], weights: [1, 0.5, 0] }), 2);
  assert.deepEqual(Array.from(session.selection()).filter((w) => w > 0), [1, 0.5]);
  const soft = session.select({ sphere: { center: [0, 0.5, 0], radius: 0.2 } }, { falloff: 0.2 });
  const weights = session.selection();
  assert.ok(weights.some((w) => w > 0 && w < 1), 'a falloff gives soft weights');
  assert.equal(weights.filter((w) => w > 0).length, soft);
  assert.equal(session.setSelection(new Float32Array(n).fill(0.25)), n);
}));

test('failed calls leave the selection, positions and rest as they were', () => withSession('closed/spool.off', (session) => {
  session.select({ sphere: { center: [0, 0.5, 0], radius: 0.5 } });
  const selection = session.selection().slice();
  const positions = session.positions().slice();
  const failures = [
    () => session.select({ sphere: { center: [0, 0, 0], radius: -1 } }),
    () => session.select({ vertices: [0, 100000] }),
    () => session.setSelection(new Float32Array(3)),
    () => session.setSelection(new Float32Array(session.info().vertices).fill(2)),
    () => session.setPositions(new Float32Array(6)),
    () => session.deform({ ...STRETCH_Y, transform: { scale: -1 } }),
    () => session.deform({ ...STRETCH_Y, pins: [100000] }),
  ];
  for (const failure of failures) {
    assert.throws(failure, AnisoformError);
    assert.deepEqual(session.selection(), selection);
    assert.deepEqual(session.positions(), positions);
  }
}));

test('exportMesh round-trips through loadMesh in every format', () => withSession('closed/torus.obj', (session) => {
  session.select({ all: true });
  session.deform({ ...STRETCH_Y, transform: { scale: 1.3 } });
  const positions = session.positions().slice();
  const info = session.info();
  const diagonal = boundingBox(positions).diagonal;
  for (const format of ['obj', 'off', 'ply', 'stl']) {
    const bytes = session.exportMesh(format);
    assert.ok(bytes instanceof Uint8Array && bytes.length > 0);
    const reader = new wasm.Session();
    try {
      const read = reader.loadMesh(bytes, `export.${format}`);
      assert.equal(read.vertices, info.vertices, format);
      assert.equal(read.triangles, info.triangles, format);
      if (format !== 'stl') {  // STL is welded, so its vertex order may differ
        assert.ok(maxVertexDistance(reader.positions(), positions) <= 1e-6 * diagonal, format);
      }
    } finally {
      reader.delete();
    }
  }
}));

test("an OBJ export after an edit keeps the loaded OBJ's texture coordinates and their corners", () => withSession('closed/spot_triangulated.obj', (session) => {
  const lines = (text, prefix) => text.split('\n').filter((line) => line.startsWith(prefix));
  const input = readFileSync(path.join(meshesDir, 'closed/spot_triangulated.obj'), 'utf8');
  session.select({ sphere: { center: [0, 0.5, 0.6], radius: 0.4 } });
  session.deform({ ...STRETCH_Y, transform: { scale: 1.3 } });
  const exported = new TextDecoder().decode(session.exportMesh('obj'));
  const coordinates = (text) => lines(text, 'vt ').map((line) => line.split(/\s+/).slice(1, 3).map(Number));
  assert.deepEqual(coordinates(exported), coordinates(input));
  // Every face as v/vt corners, the same as the file's.
  const corners = (text) => lines(text, 'f ').map((line) => line.split(/\s+/).slice(1).map((c) => c.split('/').slice(0, 2).join('/')).join(' '));
  assert.deepEqual(corners(exported), corners(input));
  assert.notDeepEqual(lines(exported, 'v '), lines(input, 'v '), 'the shape changed');
}));

test("an export after an edit keeps the input's header comments (its attribution), whatever the format", () => {
  const attribution = 'Converted by the curator from odedstein-meshes objects/spot/spot_low_resolution.obj '
    + '(Spot by Keenan Crane, public domain).';
  const expected = {
    ply: ['comment written by anisoform', `comment ${attribution}`],
    obj: ['# written by anisoform', `# ${attribution}`],
    off: ['# written by anisoform', `# ${attribution}`],
  };
  withSession('formats/spot_lowres_ascii.ply', (session) => {
    session.select({ all: true });
    session.deform({ ...STRETCH_Y, transform: { scale: 1.1 } });
    for (const [format, lines] of Object.entries(expected)) {
      // The header's text (a binary PLY's body after it is not text).
      const text = new TextDecoder('latin1').decode(session.exportMesh(format)).split('\n').slice(0, 5);
      const comments = text.filter((line) => line.startsWith('#') || line.startsWith('comment'));
      assert.deepEqual(comments, lines, format);
    }
  });
  // An OBJ's leading block goes into a PLY.
  withSession('closed/torus.obj', (session) => {
    const header = new TextDecoder('latin1').decode(session.exportMesh('ply')).split('\n').slice(2, 5);
    assert.deepEqual(header, ['comment written by anisoform', "comment Blender v2.82 (sub 7) OBJ File: ''",
      'comment www.blender.org']);
  });
});

test('a deleted session refuses calls', () => {
  const session = sessionWith(wasm, 'open/plane.off');
  session.delete();
  assert.equal(session.isDeleted(), true);
  assert.throws(() => session.info(), (error) => error instanceof AnisoformError && /deleted/.test(error.message));
  session.delete();  // twice is harmless
});

test('the loaded bytes may be an ArrayBuffer or any view', () => {
  const session = new wasm.Session();
  try {
    const bytes = meshBytes('open/plane.off');
    const copy = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
    assert.equal(session.loadMesh(copy, 'plane.off').vertices, 841);
    assert.equal(session.loadMesh(new DataView(copy), 'plane.off').vertices, 841);
  } finally {
    session.delete();
  }
});
