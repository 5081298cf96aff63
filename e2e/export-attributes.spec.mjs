// A GLB export of a mesh opened from an OBJ or a PLY keeps what that file
// carried and glTF has a place for: an OBJ's texture coordinates (split at
// the UV seams, smooth normals across them) and material names, an OBJ's or
// a PLY's vertex colours (sRGB in the file, linear in glTF). An OBJ export
// of a coloured PLY writes its colours as v x y z r g b.
import { readFileSync, writeFileSync } from 'node:fs';

import { meshesByName, parseGlb } from './gltf-scene.mjs';
import { expect, meshPath, openApp, stretchUpperHalfAndExport, test, uploadFile } from './support.mjs';

// The solver vertex at each position of `points` (exactly, in float32), or -1.
function solverVertices(points, positions) {
  const key = (x, y, z) => `${Math.fround(x)} ${Math.fround(y)} ${Math.fround(z)}`;
  const at = new Map();
  for (let v = 0; v < positions.length / 3; v++) at.set(key(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]), v);
  const out = [];
  for (let i = 0; i < points.count; i++) out.push(at.get(key(points.getX(i), points.getY(i), points.getZ(i))) ?? -1);
  return out;
}

test("an OBJ's texture coordinates go into its GLB export, split at the seams, normals smooth across them", async ({ page }) => {
  const pageErrors = await openApp(page);
  const path = meshPath('closed/spot_triangulated.obj');
  expect((await uploadFile(page, path)).ok).toBe(true);
  const edit = await stretchUpperHalfAndExport(page, 'glb', { scale: 1.4, falloff: 0.1 });
  const [mesh] = Object.values(meshesByName(await parseGlb(edit.bytes)));
  const position = mesh.geometry.getAttribute('position');
  const uv = mesh.geometry.getAttribute('uv');
  const normal = mesh.geometry.getAttribute('normal');
  expect(uv).toBeDefined();

  // The file's (vertex, vt) corner pairs.
  const lines = readFileSync(path, 'utf8').split('\n');
  const vt = lines.filter((line) => line.startsWith('vt ')).map((line) => line.split(/\s+/).slice(1, 3).map(Number));
  const pairs = new Set();
  for (const line of lines.filter((text) => text.startsWith('f '))) {
    for (const corner of line.trim().split(/\s+/).slice(1)) {
      const [v, t] = corner.split('/').map(Number);
      pairs.add(`${v - 1} ${Math.fround(vt[t - 1][0])} ${Math.fround(vt[t - 1][1])}`);
    }
  }
  // One exported vertex per distinct pair, each on its solver vertex (the
  // edited shape), the first n in the solver's order.
  const n = edit.positions.length / 3;
  const vertices = solverVertices(position, edit.positions);
  expect(position.count).toBe(pairs.size);
  expect(vertices.slice(0, n)).toEqual(Array.from({ length: n }, (_, i) => i));
  const exported = new Set(vertices.map((v, i) => `${v} ${uv.getX(i)} ${uv.getY(i)}`));
  expect(exported).toEqual(pairs);
  expect(position.count - n).toBeGreaterThan(200); // the seams' copies
  // Copies of a vertex share its normal; every normal has unit length.
  const first = new Map();
  for (let i = 0; i < position.count; i++) {
    expect(Math.hypot(normal.getX(i), normal.getY(i), normal.getZ(i))).toBeCloseTo(1, 5);
    const j = first.get(vertices[i]);
    if (j === undefined) first.set(vertices[i], i);
    else expect([normal.getX(i), normal.getY(i), normal.getZ(i)]).toEqual([normal.getX(j), normal.getY(j), normal.getZ(j)]);
  }
  // Read back, it welds to the edited mesh in its order.
  const back = await page.evaluate(async (bytes) => {
    await window.anisoform.load(new Uint8Array(bytes).buffer, 'back.glb');
    return Array.from(window.anisoform.positions());
  }, Array.from(edit.bytes));
  expect(back.length).toBe(edit.positions.length);
  back.forEach((value, k) => expect(Math.abs(value - edit.positions[k])).toBeLessThan(1e-6));
  expect(pageErrors).toEqual([]);
});

test("an OBJ's material name is its GLB export's material", async ({ page }) => {
  await openApp(page);
  expect((await uploadFile(page, meshPath('formats/concave_polygon.obj'))).ok).toBe(true);
  const edit = await stretchUpperHalfAndExport(page, 'glb', { scale: 1.4, falloff: 0.1 });
  const [mesh] = Object.values(meshesByName(await parseGlb(edit.bytes)));
  expect(mesh.material.name).toBe('test');
});

test("a PLY's vertex colours go into its GLB (linear) and OBJ (v x y z r g b) exports", async ({ page }, testInfo) => {
  const pageErrors = await openApp(page);
  // Spot's PLY with a colour per vertex (from its position), as a scanner writes one.
  const source = readFileSync(meshPath('formats/spot_lowres_ascii.ply'), 'utf8');
  const [header, body] = source.split('end_header\n');
  const rows = body.split('\n');
  const count = Number(/element vertex (\d+)/.exec(header)[1]);
  const bytes = [];
  for (let i = 0; i < count; i++) {
    const xyz = rows[i].trim().split(/\s+/).map(Number);
    const rgb = xyz.map((value) => Math.floor(127.5 * (1 + Math.tanh(3 * value))));
    bytes.push(rgb);
    rows[i] = `${rows[i].trim()} ${rgb.join(' ')}`;
  }
  const colored = header.replace('property float z\n', 'property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n') +
    'end_header\n' + rows.join('\n');
  const path = testInfo.outputPath('spot-colors.ply');
  writeFileSync(path, colored);
  expect((await uploadFile(page, path)).ok).toBe(true);

  const glb = await stretchUpperHalfAndExport(page, 'glb', { scale: 1.4, falloff: 0.1 });
  const [mesh] = Object.values(meshesByName(await parseGlb(glb.bytes)));
  const color = mesh.geometry.getAttribute('color');
  expect(color).toBeDefined();
  expect(mesh.material.vertexColors).toBe(true);
  const linear = (byte) => {
    const c = byte / 255;
    return c <= 0.04045 ? c / 12.92 : ((c + 0.055) / 1.055) ** 2.4;
  };
  const vertices = solverVertices(mesh.geometry.getAttribute('position'), glb.positions);
  for (let i = 0; i < color.count; i++) {
    // The PLY keeps its vertex order, so solver vertex v is the file's vertex v.
    const rgb = bytes[vertices[i]];
    expect(Math.abs(color.getX(i) - linear(rgb[0]))).toBeLessThan(1e-5);
    expect(Math.abs(color.getY(i) - linear(rgb[1]))).toBeLessThan(1e-5);
    expect(Math.abs(color.getZ(i) - linear(rgb[2]))).toBeLessThan(1e-5);
  }

  const obj = new TextDecoder().decode(await page.evaluate(async () => Array.from(new Uint8Array(await window.anisoform.export('obj')))).then((list) => new Uint8Array(list)));
  const vertexLines = obj.split('\n').filter((line) => line.startsWith('v '));
  expect(vertexLines).toHaveLength(count);
  vertexLines.forEach((line, v) => {
    const values = line.split(' ').slice(1).map(Number);
    expect(values).toHaveLength(6);
    values.slice(3).forEach((value, k) => expect(Math.abs(value - bytes[v][k] / 255)).toBeLessThan(1e-6));
  });
  expect(pageErrors).toEqual([]);
});
