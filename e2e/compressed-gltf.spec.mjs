// Compressed and quantized GLBs, as product models are shipped (Draco,
// meshopt, KHR_mesh_quantization), open as the shape their uncompressed file
// has, and an edit exports as a shape the file's quantization could not hold.
import { readFileSync, writeFileSync } from 'node:fs';

import { dracoGlb, instancedGlb, meshoptGlb, quantizedGlb, skinnedGlb } from './compressed-gltf.mjs';
import { assembledGlb, glbChunks, glbWithJson, meshesByName, parseGlb, spotSceneGlb, worldPositions } from './gltf-scene.mjs';
import { evaluateBulk, expect, failures, meshPath, openApp, rangeAlong, stretchUpperHalfAndExport, test, uploadFile } from './support.mjs';

const SPOT = meshPath('formats/spot_lowres.glb');

// Opens `bytes` as `name` in the app; the load's outcome, the solver's
// positions and the notice shown ('' for none).
async function open(page, bytes, name) {
  const path = test.info().outputPath(name);
  writeFileSync(path, bytes);
  const loaded = await uploadFile(page, path);
  const { positions, notice } = await evaluateBulk(page, () => {
    const shown = document.querySelector('[data-testid="notice"]');
    return { positions: Array.from(window.anisoform.positions()), notice: shown.hidden ? '' : shown.textContent };
  });
  return { ...loaded, positions, notice };
}

// The largest distance from a point of `points` to the nearest of `to` (xyz runs).
function farthestFrom(points, to) {
  let worst = 0;
  for (let i = 0; i < points.length; i += 3) {
    let nearest = Infinity;
    for (let j = 0; j < to.length; j += 3) {
      const d = (points[i] - to[j]) ** 2 + (points[i + 1] - to[j + 1]) ** 2 + (points[i + 2] - to[j + 2]) ** 2;
      if (d < nearest) nearest = d;
    }
    worst = Math.max(worst, Math.sqrt(nearest));
  }
  return worst;
}

const heightRange = (positions) => rangeAlong(positions, [0, 1, 0]);

// Every exported vertex (world coordinates) on a solver vertex.
async function exportedWorld(bytes) {
  return Object.values(meshesByName(await parseGlb(bytes))).map((mesh) => ({ mesh, world: worldPositions(mesh) }));
}

test('Draco, meshopt and quantized GLBs of a real model open as the shape of its uncompressed file', async ({ page }) => {
  const pageErrors = await openApp(page);
  const glb = readFileSync(SPOT);
  const plain = await open(page, glb, 'spot.glb');
  expect(plain.ok).toBe(true);
  const { min: lo, max: hi } = heightRange(plain.positions);
  const variants = [
    { name: 'spot-draco.glb', bytes: await dracoGlb(glb), note: 'is Draco-compressed', bits: 14 },
    { name: 'spot-quantized.glb', bytes: await quantizedGlb(glb), note: null, bits: 16 },
    { name: 'spot-meshopt.glb', bytes: await meshoptGlb(await quantizedGlb(glb)), note: 'is meshopt-compressed', bits: 16 },
  ];
  for (const variant of variants) {
    expect(variant.bytes.length, variant.name).toBeLessThan(glb.length);
    const loaded = await open(page, variant.bytes, variant.name);
    expect(loaded.ok, `${variant.name}: ${loaded.message}`).toBe(true);
    expect(loaded.info.vertices, variant.name).toBe(plain.info.vertices);
    expect(loaded.info.triangles, variant.name).toBe(plain.info.triangles);
    // Within the quantization's step (the largest extent over 2^bits), both ways.
    const step = (2 * (hi - lo)) / 2 ** variant.bits;
    expect(farthestFrom(loaded.positions, plain.positions), variant.name).toBeLessThan(step);
    expect(farthestFrom(plain.positions, loaded.positions), variant.name).toBeLessThan(step);
    if (variant.note) expect(loaded.notice).toContain(`The file's geometry ${variant.note}: a GLB export writes it uncompressed.`);
    else expect(loaded.notice).not.toContain('compressed');
  }
  expect(pageErrors).toEqual([]);
});

test('an edit of a quantized, meshopt-compressed GLB exports past the box its quantization covered', async ({ page }) => {
  const pageErrors = await openApp(page);
  const packed = await meshoptGlb(await quantizedGlb(readFileSync(SPOT)));
  const loaded = await open(page, packed, 'spot-meshopt.glb');
  expect(loaded.ok).toBe(true);
  const edit = await stretchUpperHalfAndExport(page, 'glb');
  const before = heightRange(loaded.positions);
  const after = heightRange(edit.positions);
  // The stretch reaches well above the file's top, where a 16-bit normalized
  // position written back in place would clamp at 1.
  expect(after.max - before.max).toBeGreaterThan(0.2 * (before.max - before.min));
  const [{ mesh, world }] = await exportedWorld(edit.bytes);
  expect(farthestFrom(world, edit.positions)).toBeLessThan(1e-5);
  expect(heightRange(world).max).toBeCloseTo(after.max, 5);
  expect(mesh.geometry.getAttribute('position').array).toBeInstanceOf(Float32Array);
  expect(glbChunks(edit.bytes).json.extensionsUsed ?? []).not.toContain('KHR_mesh_quantization');
  expect(pageErrors).toEqual([]);
});

test('a Draco-compressed product scene exports with its nodes, material and normals, in the edited shape', async ({ page }) => {
  const pageErrors = await openApp(page);
  const scene = await spotSceneGlb(meshPath('closed/spot_triangulated.obj'));
  const loaded = await open(page, await dracoGlb(scene), 'product-draco.glb');
  expect(loaded.ok, loaded.message).toBe(true);
  expect(loaded.notice).toContain("The file's geometry is Draco-compressed");
  const edit = await stretchUpperHalfAndExport(page, 'glb');
  expect(glbChunks(edit.bytes).json.nodes.map((node) => node.name)).toEqual(glbChunks(scene).json.nodes.map((node) => node.name));
  const parts = await exportedWorld(edit.bytes);
  expect(parts.map(({ mesh }) => mesh.name).sort()).toEqual(['body', 'copy', 'crate']);
  let moved = 0;
  const original = meshesByName(await parseGlb(scene));
  for (const { mesh, world } of parts) {
    expect(mesh.material.name, mesh.name).toBe(original[mesh.name].material.name);
    expect(farthestFrom(world, edit.positions), mesh.name).toBeLessThan(1e-5);
    moved = Math.max(moved, farthestFrom(world, loaded.positions));
    const normal = mesh.geometry.getAttribute('normal');
    expect(failures(normal.count, (i) => {
      const length = Math.hypot(normal.getX(i), normal.getY(i), normal.getZ(i));
      return !(Math.abs(length - 1) < 5e-5) && `normal of length ${length}`;
    }), mesh.name).toEqual([]);
  }
  expect(moved).toBeGreaterThan(0.1);
  expect(pageErrors).toEqual([]);
});

test('each instance of an instanced GLB mesh is edited where it lies and exports as a mesh of its own', async ({ page }) => {
  const pageErrors = await openApp(page);
  const glb = readFileSync(SPOT);
  const plain = await open(page, glb, 'spot.glb');
  const offsets = [[0, 0, 0], [3, 0, 0], [0, 0, -3]];
  const loaded = await open(page, await instancedGlb(glb, offsets), 'spot-instanced.glb');
  expect(loaded.ok, loaded.message).toBe(true);
  expect(loaded.notice).toContain('3 instances (EXT_mesh_gpu_instancing) became meshes of their own, and export as such.');
  expect(loaded.info.vertices).toBe(3 * plain.info.vertices);
  // Each instance where the file places it: Spot moved by its offset.
  for (const [k, [dx, dy, dz]] of offsets.entries()) {
    const instance = loaded.positions.slice(3 * k * plain.info.vertices, 3 * (k + 1) * plain.info.vertices);
    const moved = plain.positions.map((value, i) => value + [dx, dy, dz][i % 3]);
    expect(farthestFrom(instance, moved), `instance ${k}`).toBeLessThan(1e-5);
  }
  const edit = await stretchUpperHalfAndExport(page, 'glb');
  const parts = await exportedWorld(edit.bytes);
  expect(parts).toHaveLength(3);
  for (const { world } of parts) expect(farthestFrom(world, edit.positions)).toBeLessThan(1e-5);
  expect(glbChunks(edit.bytes).json.extensionsUsed ?? []).not.toContain('EXT_mesh_gpu_instancing');
  expect(pageErrors).toEqual([]);
});

test('a skinned (rigged) GLB mesh is edited in its rest pose and exports with its skin', async ({ page }) => {
  const pageErrors = await openApp(page);
  const glb = readFileSync(SPOT);
  const plain = await open(page, glb, 'spot.glb');
  const rigged = await skinnedGlb(glb);
  const loaded = await open(page, rigged, 'spot-rigged.glb');
  expect(loaded.ok, loaded.message).toBe(true);
  expect(loaded.notice).toContain('1 skinned (rigged) mesh is edited in the rest pose; the skin is kept.');
  expect(loaded.positions).toEqual(plain.positions);
  const edit = await stretchUpperHalfAndExport(page, 'glb');
  const [{ mesh, world }] = await exportedWorld(edit.bytes);
  expect(mesh.isSkinnedMesh).toBe(true);
  expect(mesh.skeleton.bones.map((bone) => bone.name)).toEqual(['hips', 'spine']);
  expect(farthestFrom(world, edit.positions)).toBeLessThan(1e-5);
  expect(farthestFrom(world, plain.positions)).toBeGreaterThan(0.1);
  // Each vertex keeps its joints and weights.
  const joints = mesh.geometry.getAttribute('skinIndex');
  const weights = mesh.geometry.getAttribute('skinWeight');
  expect(failures(joints.count, (i) => {
    const skin = [joints.getX(i), joints.getY(i), weights.getX(i), weights.getY(i)];
    return skin.join() !== '0,1,0.5,0.5' && `joints ${skin.slice(0, 2)}, weights ${skin.slice(2)}`;
  })).toEqual([]);
  expect(pageErrors).toEqual([]);
});

test('a GLB using an extension the app does not read says which, and still opens', async ({ page }) => {
  const pageErrors = await openApp(page);
  const glb = readFileSync(SPOT);
  const { json, bin } = glbChunks(glb);
  json.extensionsUsed = ['KHR_texture_basisu', 'KHR_materials_unlit'];
  const loaded = await open(page, assembledGlb(json, bin), 'spot-basisu.glb');
  expect(loaded.ok).toBe(true);
  expect(loaded.notice).toContain(
    'The file uses glTF extensions this app does not read (KHR_texture_basisu): what they add is not shown, and a GLB export leaves it out.',
  );
  expect(pageErrors).toEqual([]);
});

test('a damaged Draco or meshopt GLB is refused, saying what failed, and the mesh stays', async ({ page }) => {
  const pageErrors = await openApp(page);
  const glb = readFileSync(SPOT);
  const before = await evaluateBulk(page, () => Array.from(window.anisoform.positions()));
  const cases = [
    ['spot-draco.glb', await dracoGlb(glb), /not a readable glTF file: Draco geometry: .*Decoding failed/],
    ['spot-meshopt.glb', await meshoptGlb(await quantizedGlb(glb)), /not a readable glTF file: Malformed buffer data/],
  ];
  for (const [name, bytes, message] of cases) {
    // Every 7th byte of the binary chunk's payload flipped.
    const damaged = Buffer.from(bytes);
    for (let i = 36 + bytes.readUInt32LE(12); i < damaged.length; i += 7) damaged[i] ^= 0x5a;
    const outcome = await open(page, damaged, name);
    expect(outcome.ok, name).toBe(false);
    expect(outcome.message).toMatch(message);
    expect(outcome.message).toContain('The current mesh (spot_triangulated.obj) is unchanged.');
    expect(outcome.positions).toEqual(before);
  }
  // No scene (GLTFLoader gives none: a TypeError was shown), and a bufferView's
  // stride of 0.5 (its positions read as NaN, said of a merged vertex number).
  const malformed = [
    ['no-scene.glb', glbWithJson(glb, (json) => { json.scenes = []; delete json.scene; }),
      /no-scene\.glb: the glTF file has no scene \(its "scenes" list is empty or missing\)/],
    ['half-stride.glb', glbWithJson(glb, (json) => {
      json.bufferViews[json.accessors[json.meshes[0].primitives[0].attributes.POSITION].bufferView].byteStride = 0.5;
    }), /half-stride\.glb: mesh '.*' has a non-finite position at its vertex \d+ \(its POSITION accessor or bufferView is malformed\)/],
  ];
  for (const [name, bytes, message] of malformed) {
    const outcome = await open(page, bytes, name);
    expect(outcome.ok, name).toBe(false);
    expect(outcome.message).toMatch(message);
    expect(outcome.positions).toEqual(before);
  }
  expect(pageErrors).toEqual([]);
});
