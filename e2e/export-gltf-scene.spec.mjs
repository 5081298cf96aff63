// A glTF file exports back as itself with the edited shape: its nodes and
// their transforms, materials, textures, UVs and vertex colours are kept, each
// primitive's vertices (split at UV seams in the file) land where the solver
// put their welded vertex, and the normals stay smooth across the seams.
import { readFileSync, writeFileSync } from 'node:fs';

import {
  glbChunks, meshesByName, parseGlb, spotSceneGlb, withBaseColorTexture, worldPositions,
} from './gltf-scene.mjs';
import { evaluateBulk, expect, exportedBytes, farFrom, meshPath, openApp, test, uploadFile } from './support.mjs';

// Deforms the part of what is loaded inside `box` (soft border) and exports
// it as GLB; returns the solver's positions before and after, and the file.
async function stretchAndExport(page, box) {
  const { rest, positions } = await evaluateBulk(page, async (region) => {
    const api = window.anisoform;
    const rest = Array.from(api.positions());
    await api.select({ box: region }, { falloff: 0.2 });
    await api.deform({ method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: [1.4, 1] } });
    return { rest, positions: Array.from(api.positions()) };
  }, box);
  return { rest, positions, bytes: await exportedBytes(page, 'glb') };
}

// Over the vertices of `mesh` (exported) and `original` (the file loaded):
// the largest distance from an exported vertex to the solver vertex its
// original became (the one at its float32 world position in the rest pose,
// as the page's importer computed it), and the largest move from the file.
function placement(mesh, original, { rest, positions }) {
  const key = (x, y, z) => `${Math.fround(x)},${Math.fround(y)},${Math.fround(z)}`;
  const solverVertex = new Map();
  for (let v = 0; v < rest.length; v += 3) solverVertex.set(key(rest[v], rest[v + 1], rest[v + 2]), v);
  const exported = worldPositions(mesh);
  const before = worldPositions(original);
  let worst = 0, moved = 0;
  for (let i = 0; i < exported.length; i += 3) {
    const v = solverVertex.get(key(before[i], before[i + 1], before[i + 2]));
    const gap = v === undefined ? Infinity
      : Math.hypot(exported[i] - positions[v], exported[i + 1] - positions[v + 1], exported[i + 2] - positions[v + 2]);
    worst = Math.max(worst, gap);
    moved = Math.max(moved, Math.hypot(exported[i] - before[i], exported[i + 1] - before[i + 1], exported[i + 2] - before[i + 2]));
  }
  return { worst, moved };
}

// A 4x4 PNG with a different colour in each pixel, drawn by the browser.
const texturePng = (page) => page.evaluate(() => {
  const canvas = Object.assign(document.createElement('canvas'), { width: 4, height: 4 });
  const context = canvas.getContext('2d');
  for (let i = 0; i < 16; i++) {
    context.fillStyle = `rgb(${i * 16}, ${255 - i * 16}, ${(i * 97) % 256})`;
    context.fillRect(i % 4, Math.floor(i / 4), 1, 1);
  }
  return canvas.toDataURL('image/png');
}).then((url) => Buffer.from(url.slice(url.indexOf(',') + 1), 'base64'));

// The RGBA pixels of PNG bytes, decoded by the browser (both ways as base64
// text: arrays of numbers cross to and from the page an entry at a time).
const pixelsOf = (page, png) => page.evaluate(async (base64) => {
  const bytes = Uint8Array.from(atob(base64), (c) => c.charCodeAt(0));
  const bitmap = await createImageBitmap(new Blob([bytes], { type: 'image/png' }));
  const canvas = Object.assign(document.createElement('canvas'), { width: bitmap.width, height: bitmap.height });
  const context = canvas.getContext('2d');
  context.drawImage(bitmap, 0, 0);
  const reader = new FileReader();
  const url = new Promise((resolve) => (reader.onload = () => resolve(reader.result)));
  reader.readAsDataURL(new Blob([context.getImageData(0, 0, bitmap.width, bitmap.height).data]));
  const text = await url;
  return text.slice(text.indexOf(',') + 1);
}, Buffer.from(png).toString('base64'));

// The bytes of a GLB's one image.
function imageOf(glb) {
  const { json, bin } = glbChunks(glb);
  expect(json.images).toHaveLength(1);
  const view = json.bufferViews[json.images[0].bufferView];
  return bin.subarray(view.byteOffset ?? 0, (view.byteOffset ?? 0) + view.byteLength);
}

test('a glTF scene exports as itself with the edited shape: nodes, material, texture, UVs, smooth normals', async ({ page }, testInfo) => {
  const pageErrors = await openApp(page);
  const png = await texturePng(page);
  const glb = withBaseColorTexture(await spotSceneGlb(meshPath('closed/spot_triangulated.obj')), png);
  const input = testInfo.outputPath('spot-scene.glb');
  writeFileSync(input, glb);
  const loaded = await uploadFile(page, input);
  expect(loaded.ok).toBe(true);
  // Two Spots, each welded at its UV seams: 3225 -> 2930 vertices.
  expect(loaded.info.vertices).toBe(2 * 2930 + 8);

  const original = meshesByName(await parseGlb(glb));
  // The body's upper half in world coordinates (its world box, cut at half height).
  const world = worldPositions(original.body);
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < world.length; i++) {
    lo[i % 3] = Math.min(lo[i % 3], world[i]);
    hi[i % 3] = Math.max(hi[i % 3], world[i]);
  }
  const box = { min: [lo[0] - 0.01, (lo[1] + hi[1]) / 2, lo[2] - 0.01], max: [hi[0] + 0.01, hi[1] + 0.01, hi[2] + 0.01] };
  const edit = await stretchAndExport(page, box);
  const exported = meshesByName(await parseGlb(edit.bytes));

  // The scene as it was: the nodes (no wrapper added), their parent and
  // transforms, the material and its texture (pixel for pixel).
  expect(glbChunks(edit.bytes).json.nodes.map((node) => node.name)).toEqual(glbChunks(glb).json.nodes.map((node) => node.name));
  expect(Object.keys(exported).sort()).toEqual(['body', 'copy', 'crate']);
  expect(glbChunks(edit.bytes).json.materials[0].pbrMetallicRoughness.baseColorTexture.index).toBe(0);
  expect(await pixelsOf(page, imageOf(edit.bytes))).toEqual(await pixelsOf(page, png));
  for (const name of ['body', 'copy', 'crate']) {
    expect(exported[name].parent.name).toBe('product');
    // (Written as translation, rotation and scale again: equal to float32 rounding.)
    const matrix = exported[name].matrixWorld.toArray();
    original[name].matrixWorld.toArray().forEach((value, k) => expect(matrix[k]).toBeCloseTo(value, 6));
    expect(exported[name].material.name).toBe('Hide');
    expect(exported[name].material.color.getHex()).toBe(original[name].material.color.getHex());
    // The UVs, bitwise.
    expect(Array.from(exported[name].geometry.getAttribute('uv').array))
      .toEqual(Array.from(original[name].geometry.getAttribute('uv').array));
  }

  // Every file vertex sits on its solver vertex; the body moved, the copy (3
  // units away, unselected) did not.
  const body = placement(exported.body, original.body, edit);
  const copy = placement(exported.copy, original.copy, edit);
  expect(body.worst).toBeLessThan(1e-5);
  expect(copy.worst).toBeLessThan(1e-5);
  expect(body.moved).toBeGreaterThan(0.3);
  expect(copy.moved).toBeLessThan(1e-5);

  // Smooth across the UV seams: the copies of a vertex in the file have one normal.
  const normals = exported.body.geometry.getAttribute('normal');
  const bodyWorld = worldPositions(exported.body);
  const byPlace = new Map();
  let seamPairs = 0, worstSeam = 0;
  for (let i = 0; i < normals.count; i++) {
    const place = `${bodyWorld[3 * i]},${bodyWorld[3 * i + 1]},${bodyWorld[3 * i + 2]}`;
    const first = byPlace.get(place);
    if (first === undefined) {
      byPlace.set(place, i);
      continue;
    }
    seamPairs++;
    const dot = normals.getX(i) * normals.getX(first) + normals.getY(i) * normals.getY(first) + normals.getZ(i) * normals.getZ(first);
    worstSeam = Math.max(worstSeam, 1 - dot);
  }
  expect(seamPairs).toBeGreaterThan(200);
  expect(worstSeam).toBeLessThan(1e-6);
  // The crate's edges stay hard: each corner keeps its face's normal (one
  // normal per welded corner would be the mean of three faces).
  const crateNormals = Array.from(exported.crate.geometry.getAttribute('normal').array);
  const crateBefore = Array.from(original.crate.geometry.getAttribute('normal').array);
  expect(farFrom(crateNormals, crateBefore, 5e-6)).toEqual([]);
  expect(pageErrors).toEqual([]);
});

test('vertex colours of a third-party GLB survive an edit and its export', async ({ page }) => {
  await openApp(page);
  const sponge = meshPath('formats/mengerSponge3.glb');
  const loaded = await uploadFile(page, sponge);
  expect(loaded.ok).toBe(true);
  const original = Object.values(meshesByName(await parseGlb(readFileSync(sponge))));
  const edit = await stretchAndExport(page, { min: [-10, 0, -10], max: [10, 10, 10] });
  const exported = Object.values(meshesByName(await parseGlb(edit.bytes)));
  expect(exported.length).toBe(original.length);
  for (const [k, mesh] of exported.entries()) {
    expect(Array.from(mesh.geometry.getAttribute('color').array))
      .toEqual(Array.from(original[k].geometry.getAttribute('color').array));
    const { worst, moved } = placement(mesh, original[k], edit);
    expect(worst).toBeLessThan(1e-5);
    expect(moved).toBeGreaterThan(0.05);
  }
});
