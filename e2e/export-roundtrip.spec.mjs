// Export, then load the exported bytes back: the same positions within float
// precision (OBJ, PLY and GLB keep the vertex order; STL has no index, so
// its welded vertices are compared as sorted lists). The OBJ keeps the
// loaded OBJ's texture coordinates.
import { expect, openApp, test } from './support.mjs';

test('export round-trips in OBJ, PLY, STL and GLB', async ({ page }) => {
  await openApp(page);
  const results = await page.evaluate(async () => {
    const api = window.anisoform;
    await api.select({ sphere: { center: [0, 0.5, 0.6], radius: 0.35 } }, { falloff: 0.15 });
    await api.deform({ method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: [1.3, 1] } });
    const edited = api.positions();
    const sortedRows = (positions) => {
      const rows = [];
      for (let i = 0; i < positions.length; i += 3) rows.push([positions[i], positions[i + 1], positions[i + 2]]);
      return rows.sort((a, b) => a[0] - b[0] || a[1] - b[1] || a[2] - b[2]).flat();
    };
    const worstDifference = (a, b) => {
      if (a.length !== b.length) return Infinity;
      let worst = 0;
      for (let i = 0; i < a.length; i++) worst = Math.max(worst, Math.abs(a[i] - b[i]));
      return worst;
    };
    // Export everything first: each load below replaces the edited mesh.
    const exported = {};
    for (const format of ['obj', 'ply', 'stl', 'glb']) exported[format] = await api.export(format);
    // Spot's OBJ has texture coordinates (3225, split at the seams): the OBJ export keeps them.
    const objLines = new TextDecoder().decode(exported.obj).split('\n');
    const texture = { vt: objLines.filter((line) => line.startsWith('vt ')).length, firstFace: objLines.find((line) => line.startsWith('f ')) };
    const results = {};
    for (const [format, bytes] of Object.entries(exported)) {
      const counts = await api.load(bytes, `roundtrip.${format}`);
      const loaded = api.positions();
      results[format] = {
        counts,
        difference: format === 'stl'
          ? worstDifference(sortedRows(edited), sortedRows(loaded))
          : worstDifference(edited, loaded),
      };
    }
    return { results, vertices: edited.length / 3, texture };
  });
  expect(results.texture).toEqual({ vt: 3225, firstFace: 'f 739/1 735/2 736/3' });
  for (const [format, { counts, difference }] of Object.entries(results.results)) {
    expect(counts.vertices, format).toBe(results.vertices);
    expect(counts.triangles, format).toBe(5856);
    expect(difference, format).toBeLessThan(1e-6);
  }
});
