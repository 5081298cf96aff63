// A GLB export of a mesh opened from an OBJ or a PLY keeps what that file
// carried and glTF has a place for: an OBJ's texture coordinates (split at
// the UV seams, smooth normals across them) and material names, an OBJ's or
// a PLY's vertex colours (sRGB in the file, linear in glTF). An OBJ export
// of a coloured PLY writes its colours as v x y z r g b.
import { readFileSync, writeFileSync } from 'node:fs';

import { meshesByName, parseGlb } from './gltf-scene.mjs';
import { expect, exportedBytes, failures, farFrom, meshPath, openApp, stretchUpperHalfAndExport, test, uploadFile } from './support.mjs';

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
  const normalOf = (i) => [normal.getX(i), normal.getY(i), normal.getZ(i)];
  expect(failures(position.count, (i) => {
    const length = Math.hypot(...normalOf(i));
    if (!(Math.abs(length - 1) < 5e-6)) return `normal of length ${length}`;
    const j = first.get(vertices[i]);
    if (j === undefined) first.set(vertices[i], i);
    else if (normalOf(i).some((value, k) => value !== normalOf(j)[k])) return `normal ${normalOf(i)}, its copy ${j}'s ${normalOf(j)}`;
    return null;
  })).toEqual([]);
  // Read back, it welds to the edited mesh in its order.
  const back = await page.evaluate(async (base64) => {
    await window.anisoform.load(Uint8Array.from(atob(base64), (c) => c.charCodeAt(0)).buffer, 'back.glb');
    return Array.from(window.anisoform.positions());
  }, edit.bytes.toString('base64'));
  expect(back.length).toBe(edit.positions.length);
  expect(farFrom(back, edit.positions, 1e-6)).toEqual([]);
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
  // The PLY keeps its vertex order, so solver vertex v is the file's vertex v.
  const exportedColours = Array.from({ length: color.count }, (_, i) => [color.getX(i), color.getY(i), color.getZ(i)]).flat();
  const fileColours = Array.from({ length: color.count }, (_, i) => bytes[vertices[i]].map(linear)).flat();
  expect(farFrom(exportedColours, fileColours, 1e-5)).toEqual([]);

  const obj = (await exportedBytes(page, 'obj')).toString('utf8');
  const vertexLines = obj.split('\n').filter((line) => line.startsWith('v '));
  expect(vertexLines).toHaveLength(count);
  const values = vertexLines.map((line) => line.split(' ').slice(1).map(Number));
  expect(failures(values.length, (v) => values[v].length !== 6 && `${values[v].length} numbers`)).toEqual([]);
  expect(farFrom(values.flatMap((line) => line.slice(3)), bytes.slice(0, values.length).flat().map((byte) => byte / 255), 1e-6)).toEqual([]);
  expect(pageErrors).toEqual([]);
});
