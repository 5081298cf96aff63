// Loading meshes into a session: every format the core reads, the mesh
// problems reported in plain words, and every malformed file refused with the
// right code and a message that names the problem, keeping the previous mesh.
import assert from 'node:assert/strict';
import { readdirSync } from 'node:fs';
import path from 'node:path';
import { before, test } from 'node:test';

import { loadAnisoform, meshBytes, meshesDir, sessionWith } from '../node-support.mjs';
import { subdivided } from '../subdivided-mesh.mjs';

let wasm;
let AnisoformError;
before(async () => {
  ({ wasm, AnisoformError } = await loadAnisoform());
});

const CORE_FORMATS = ['.obj', '.off', '.ply', '.stl'];

test('every obj/off/ply/stl file in formats/ loads as a clean triangle mesh', () => {
  const session = new wasm.Session();
  try {
    const files = readdirSync(path.join(meshesDir, 'formats'))
      .filter((name) => CORE_FORMATS.includes(path.extname(name)));
    assert.ok(files.length >= 10, `expected the formats/ meshes, found ${files.length}`);
    for (const name of files) {
      const info = session.loadMesh(meshBytes(`formats/${name}`), name);
      assert.ok(info.vertices > 0 && info.triangles > 0, name);
      assert.equal(session.positions().length, 3 * info.vertices, name);
      assert.equal(session.triangles().length, 3 * info.triangles, name);
      assert.equal(session.selection().length, info.vertices, name);
    }
  } finally {
    session.delete();
  }
});

test('spot_lowres reads to the same mesh from OBJ, OFF, PLY and STL, ascii and binary', () => {
  const session = new wasm.Session();
  try {
    const counts = ['spot_lowres.obj', 'spot_lowres.off', 'spot_lowres_ascii.ply', 'spot_lowres_binary.ply',
      'spot_lowres_ascii.stl', 'spot_lowres_binary.stl'].map((name) => {
      const info = session.loadMesh(meshBytes(`formats/${name}`), name);
      return `${info.vertices}/${info.triangles}/${info.components}/${info.boundaryLoops}`;
    });
    assert.equal(new Set(counts).size, 1, counts.join(' '));
  } finally {
    session.delete();
  }
});

test('polygon files are triangulated and say so in the notes', () => {
  const session = new wasm.Session();
  try {
    const info = session.loadMesh(meshBytes('formats/spot_quadrangulated.obj'), 'spot_quadrangulated.obj');
    assert.ok(info.notes.some((note) => /triangulated/.test(note)), info.notes.join(' | '));
    assert.equal(info.edgeManifold, true);
  } finally {
    session.delete();
  }
});

test('GLB files are refused as bad-parameter: the core reads obj/off/ply/stl only', () => {
  const session = new wasm.Session();
  try {
    assert.throws(() => session.loadMesh(meshBytes('formats/box.glb'), 'box.glb'),
      (error) => error instanceof AnisoformError && error.code === 'bad-parameter' && /GLB/.test(error.message));
  } finally {
    session.delete();
  }
});

test('info of an open mesh counts its boundary loops; closed meshes have none', () => {
  for (const [file, loops] of [['open/plane.off', 1], ['closed/torus.obj', 0], ['open/stanford-bunny.obj', 5]]) {
    const session = sessionWith(wasm, file);
    try {
      const info = session.info();
      assert.equal(info.boundaryLoops, loops, file);
      assert.equal(info.components, 1, file);
    } finally {
      session.delete();
    }
  }
});

// The malformed files the session must refuse: code and what the message names.
const REFUSED = {
  'bad_index_out_of_range.obj': ['bad-file', /face \d+ references vertex \d+.*\(line \d+\)/],
  'bad_index_out_of_range.off': ['bad-file', /face \d+ references vertex 829.*\(line \d+\)/],
  // Counted from 0, and an OBJ's message says so: its 'f' lines count from 1.
  'bad_nan_coordinate.obj': ['bad-mesh', /vertex 5 has a non-finite coordinate .*; vertices and faces are counted from 0 here: vertex 0 is the file's first 'v' line/],
  'boxNotManifold.glb': ['bad-parameter', /GLB/],
  'empty.obj': ['bad-file', /empty/],
  'empty.off': ['bad-file', /empty/],
  'empty.ply': ['bad-file', /empty/],
  'empty.stl': ['bad-file', /empty/],
  'empty_mesh_header_only.off': ['bad-mesh', /no vertices/],
  'empty_mesh_header_only.ply': ['bad-mesh', /no vertices/],
  'empty_mesh_zero_triangles.stl': ['bad-mesh', /no triangles/],
  'number_formats.obj': ['bad-file', /'3\.1\+e2' is not a number \(line 11\)/],
  'truncated_binary.ply': ['bad-file', /truncated/],
  'truncated_binary.stl': ['bad-file', /truncated/],
};

// The ones it repairs or solves through, and what info must then report.
const ACCEPTED = {
  'Spider_binary.stl': (info) => info.notes.some((n) => /welded/.test(n)),
  'bad_degenerate_faces.obj': (info) => info.problems.some((p) => p.kind === 'zero-area-triangle' && /face 800/.test(p.message)),
  'bad_flipped_faces.obj': (info) => !info.consistentlyOriented && info.problems.some((p) => p.kind === 'inconsistent-orientation')
    && info.notes.includes("vertices and faces are counted from 0 here: vertex 0 is the file's first 'v' line, face 0 its first triangle"),
  'bad_nonmanifold_edge.obj': (info) => !info.edgeManifold && info.problems.some((p) => p.kind === 'non-manifold-edge' && /edge \(44, 66\)/.test(p.message)),
  // Welded: its vertices are numbered anew, not as its 'v' lines.
  'bad_triangle_soup.obj': (info) => info.vertices === 829 && info.notes.some((n) => /triangle soup/.test(n))
    && !info.notes.some((n) => /counted from 0/.test(n)),
  'boxNotManifold.obj': (info) => info.vertices > 0,
  'box_UTF16BE.obj': (info) => info.notes.some((n) => /UTF-16/.test(n)),
  'box_without_lineending.obj': (info) => info.triangles === 12,
  // OFF counts from 0 itself: nothing to say.
  'degtri_sliding.off': (info) => info.degenerateTriangles > 0 && !info.notes.some((n) => /counted from 0/.test(n)),
  'multi_component.obj': (info) => info.components > 1,
  'openscad-nonmanifold-crash.obj': (info) => info.problems.length > 0,
  'testmixed.obj': (info) => info.notes.some((n) => /skipped/.test(n)),
};

test('every malformed file is refused with its code and a message naming the problem, or repaired and reported', () => {
  const files = readdirSync(path.join(meshesDir, 'malformed'));
  const unlisted = files.filter((name) => !(name in REFUSED) && !(name in ACCEPTED));
  assert.deepEqual(unlisted, [], 'every malformed file has an expectation');
  const session = sessionWith(wasm, 'closed/spool.off');
  try {
    const keptPositions = session.positions().slice();
    const keptInfo = session.info();
    for (const name of files) {
      const bytes = meshBytes(`malformed/${name}`);
      if (name in REFUSED) {
        const [code, pattern] = REFUSED[name];
        assert.throws(() => session.loadMesh(bytes, name), (error) => {
          assert.ok(error instanceof AnisoformError, `${name}: ${error}`);
          assert.equal(error.code, code, `${name}: ${error.message}`);
          assert.match(error.message, pattern, name);
          assert.ok(error.message.includes(name), `${name}: the message names the file: ${error.message}`);
          return true;
        });
        // The session keeps the mesh it had.
        assert.deepEqual(session.info(), keptInfo, name);
        assert.deepEqual(session.positions(), keptPositions, name);
      } else {
        const info = session.loadMesh(bytes, name);
        assert.ok(ACCEPTED[name](info), `${name}: ${JSON.stringify({ problems: info.problems.slice(0, 3), notes: info.notes })}`);
        session.loadMesh(meshBytes('closed/spool.off'), 'spool.off');
      }
    }
  } finally {
    session.delete();
  }
});

test('setMesh takes flat arrays, welds on request and refuses out-of-range indices', () => {
  const session = new wasm.Session();
  try {
    // Two triangles of a square sharing corner 0; corner 4 repeats corner 2.
    const positions = new Float32Array([0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 1, 1, 0]);
    const corners = new Uint32Array([0, 1, 2, 0, 4, 3]);
    assert.equal(session.setMesh(positions, corners).vertices, 5);
    assert.deepEqual(Array.from(session.inputVertexMap()), [0, 1, 2, 3, 4]);
    const welded = session.setMesh(positions, corners, { weld: true });
    assert.equal(welded.vertices, 4);
    // Where each input vertex went: corner 4 onto corner 2.
    assert.deepEqual(Array.from(session.inputVertexMap()), [0, 1, 2, 3, 2]);
    assert.equal(welded.triangles, 2);
    assert.equal(welded.boundaryLoops, 1);
    assert.ok(welded.notes.some((n) => /welded/.test(n)));
    // A soup (no shared vertex at all) is welded whatever `weld` says, as files are.
    const soup = new Float32Array([0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 0, 0, 1, 1, 0, 0, 1, 0]);
    assert.equal(session.setMesh(soup, new Uint32Array([0, 1, 2, 3, 4, 5])).vertices, 4);
    const map = session.inputVertexMap();
    const loaded = session.positions();
    for (let i = 0; i < 6; i++) {
      assert.deepEqual(Array.from(loaded.subarray(3 * map[i], 3 * map[i] + 3)), Array.from(soup.subarray(3 * i, 3 * i + 3)));
    }
    assert.throws(() => session.setMesh(soup, new Uint32Array([0, 1, 6])),
      (error) => error.code === 'bad-mesh' && /triangle 0 references vertex 6, but there are only 6 vertices/.test(error.message));
    assert.throws(() => session.setMesh(soup, new Uint32Array([0, 1, 2, 3])),
      (error) => error.code === 'bad-parameter' && /3 indices per triangle/.test(error.message));
    assert.equal(session.info().vertices, 4, 'a refused setMesh keeps the mesh');
    assert.equal(session.inputVertexMap().length, 6, 'and its map');
    session.loadMesh(meshBytes('formats/spot_lowres.off'), 'spot_lowres.off');
    assert.equal(session.inputVertexMap().length, 0, 'a file has no input arrays to map');
  } finally {
    session.delete();
  }
});

test("surfaceAttributes gives a file's texture per corner, its colours in [0, 1] and its materials", () => {
  const session = new wasm.Session();
  try {
    const spot = session.loadMesh(meshBytes('closed/spot_triangulated.obj'), 'spot_triangulated.obj');
    const textured = session.surfaceAttributes();
    assert.equal(textured.cornerUv.length, 6 * spot.triangles);
    // Corner 0 of triangle 0 is the file's first face's first vt ("f 739/1 ..."), as float32.
    const text = new TextDecoder().decode(meshBytes('closed/spot_triangulated.obj'));
    const vt1 = /\nvt ([^\n]+)/.exec(text)[1].trim().split(/\s+/).slice(0, 2).map(Number);
    assert.deepEqual(Array.from(textured.cornerUv.subarray(0, 2)), vt1.map(Math.fround));
    assert.equal(textured.colors, null);
    assert.deepEqual(textured.materials, []);
    session.loadMesh(meshBytes('formats/concave_polygon.obj'), 'concave_polygon.obj');
    assert.deepEqual(session.surfaceAttributes().materials, [{ name: 'test', first: 0 }]);
    // A PLY's red, green, blue bytes as colours in [0, 1].
    const ply = 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n' +
      'property uchar red\nproperty uchar green\nproperty uchar blue\nelement face 1\nproperty list uchar int vertex_indices\n' +
      'end_header\n0 0 0 255 0 51\n1 0 0 0 255 0\n0 1 0 0 0 255\n3 0 1 2\n';
    session.loadMesh(new TextEncoder().encode(ply), 'colored.ply');
    const colored = session.surfaceAttributes();
    assert.deepEqual(Array.from(colored.colors), [1, 0, 0.2, 0, 1, 0, 0, 0, 1].map(Math.fround));
    assert.equal(colored.cornerUv, null);
  } finally {
    session.delete();
  }
});

test('calls before any mesh is loaded fail with bad-parameter', () => {
  const session = new wasm.Session();
  try {
    for (const call of [() => session.info(), () => session.positions(), () => session.select({ all: true }),
      () => session.deform({}), () => session.commit(), () => session.exportMesh('obj')]) {
      assert.throws(call, (error) => error instanceof AnisoformError && error.code === 'bad-parameter' && /no mesh/.test(error.message));
    }
  } finally {
    session.delete();
  }
});

test('the benchmarks\' build: cappedCylinder gives a closed, consistently oriented cylinder of about N vertices', async () => {
  const { wasm: benchWasm } = await loadAnisoform({ bench: true });
  assert.equal(wasm.cappedCylinder, undefined, 'bench-only code stays out of the shipped module');
  assert.equal(wasm.LaplacianFloor, undefined);
  const session = new benchWasm.Session();
  try {
    for (const n of [1000, 10000]) {
      const { positions, triangles } = benchWasm.cappedCylinder(n);
      const info = session.setMesh(positions, triangles);
      assert.ok(Math.abs(info.vertices - n) <= 0.05 * n, `${info.vertices} vertices for ${n}`);
      assert.equal(info.triangles, 2 * info.vertices - 4, 'a closed genus-0 triangle mesh');
      assert.deepEqual([info.components, info.boundaryLoops, info.edgeManifold, info.consistentlyOriented, info.degenerateTriangles],
        [1, 0, true, true, 0]);
      assert.deepEqual([info.bbox.min[2], info.bbox.max[2]], [-2, 2], 'height 4, centred');
      let radius = 0;
      for (let i = 0; i < positions.length; i += 3) radius = Math.max(radius, Math.hypot(positions[i], positions[i + 1]));
      assert.ok(Math.abs(radius - 1) < 1e-12, `radius ${radius}`);
    }
    assert.throws(() => benchWasm.cappedCylinder(10), (error) => error.code === 'bad-parameter' && /16/.test(error.message));
  } finally {
    session.delete();
  }
});

test('a mesh too big to edit within the module memory is refused at once, naming both numbers; the previous mesh stays', () => {
  const session = new wasm.Session();
  try {
    // 2 GB over the 4 KB an edit needs per vertex.
    assert.equal(session.vertexLimit(), 2 ** 31 / 4096);
    session.loadMesh(meshBytes('large/koala_loop1_200k.ply'), 'koala_loop1_200k.ply');
    const before = session.positions().slice();
    const big = subdivided(session.positions(), session.triangles());
    assert.equal(big.positions.length / 3, 799954);
    const started = performance.now();
    assert.throws(() => session.setMesh(big.positions, big.triangles), (error) => {
      assert.ok(error instanceof AnisoformError);
      assert.equal(error.code, 'bad-mesh');
      assert.match(error.message, /799954 vertices, more than the 524288 that can be edited here/);
      assert.match(error.message, /2 GB/);
      return true;
    });
    console.log(`an 800k-vertex mesh refused after ${Math.round(performance.now() - started)} ms`);
    assert.equal(session.info().vertices, 199990);
    assert.deepEqual(session.positions(), before);
  } finally {
    session.delete();
  }
});
