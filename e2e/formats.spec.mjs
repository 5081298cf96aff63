// Every file of shared/meshes/formats uploads through the file input and
// gives the counts of MANIFEST.md (polygons triangulated, STL soups welded).
// A .gltf whose geometry is in another file is refused, naming that file.
import { readdirSync, readFileSync, writeFileSync } from 'node:fs';
import { evaluateBulk, expect, meshesDir, meshPath, openApp, test, uploadFile } from './support.mjs';

// triangles = sum over polygons of (corners - 2)
const EXPECTED = {
  'spot_lowres.obj': [829, 1654],
  'spot_lowres.off': [829, 1654],
  'spot_lowres_ascii.ply': [829, 1654],
  'spot_lowres_binary.ply': [829, 1654],
  'spot_lowres_binary.stl': [829, 1654],
  'spot_lowres_ascii.stl': [829, 1654],
  'spot_lowres.glb': [829, 1654],
  'fandisk_binary.stl': [6475, 12946],
  'armadillo_binary.ply': [26002, 52000],
  'spot_quadrangulated.obj': [2930, 2 * 2928],
  'spot_control_mesh.obj': [188, 4 + 2 * 160 + 3 * 16],
  'concave_polygon.obj': [64, 64],
  'mengerSponge3.glb': [7983, 21598],
  'box.glb': [8, 12],
};

const files = readdirSync(`${meshesDir}/formats`).filter((name) => !name.endsWith('.mtl'));

test('every file in formats/ has an expected count', () => {
  expect(files.sort()).toEqual(Object.keys(EXPECTED).sort());
});

test.describe('uploading every format', () => {
  let page;
  test.beforeAll(async ({ browser }) => {
    page = await browser.newPage();
    await openApp(page);
  });
  test.afterAll(() => page.close());

  for (const name of Object.keys(EXPECTED)) {
    test(name, async () => {
      const outcome = await uploadFile(page, meshPath(`formats/${name}`));
      expect(outcome).toMatchObject({ ok: true });
      const [vertices, triangles] = EXPECTED[name];
      expect(outcome.info).toMatchObject({ vertices, triangles });
      await expect(page.getByTestId('error')).toBeHidden();
    });
  }
});

test('dropping a file on the page loads it', async ({ page }) => {
  await openApp(page);
  const base64 = readFileSync(meshPath('formats/spot_lowres.off')).toString('base64');
  const loaded = page.evaluate(
    () =>
      new Promise((resolve) => {
        const off = window.anisoform.on('change', ({ reason }) => {
          if (reason === 'load') {
            off();
            resolve(window.anisoform.info());
          }
        });
      }),
  );
  const dataTransfer = await page.evaluateHandle((data) => {
    const transfer = new DataTransfer();
    transfer.items.add(new File([Uint8Array.from(atob(data), (c) => c.charCodeAt(0))], 'spot_lowres.off'));
    return transfer;
  }, base64);
  await page.dispatchEvent('main.viewport', 'dragenter', { dataTransfer });
  await expect(page.getByTestId('drop-overlay')).toBeVisible();
  await page.dispatchEvent('main.viewport', 'drop', { dataTransfer });
  expect(await loaded).toMatchObject({ vertices: 829, triangles: 1654 });
  await expect(page.getByTestId('drop-overlay')).toBeHidden();
});

test('a .gltf with its buffers embedded as data: URIs opens under the strict CSP, as its GLB does', async ({ page }, testInfo) => {
  const pageErrors = await openApp(page);
  // spot_lowres.glb as a .gltf: its binary chunk a base64 data: URI, after
  // a small first buffer that no view uses (so the views' buffer is 1).
  const glb = readFileSync(meshPath('formats/spot_lowres.glb'));
  const jsonLength = glb.readUInt32LE(12);
  const json = JSON.parse(glb.subarray(20, 20 + jsonLength).toString('utf8'));
  const bin = glb.subarray(28 + jsonLength, 28 + jsonLength + glb.readUInt32LE(20 + jsonLength));
  json.buffers = [
    { uri: 'data:application/octet-stream;base64,AAECAwQ=', byteLength: 5 },
    { uri: `data:application/octet-stream;base64,${bin.toString('base64')}`, byteLength: json.buffers[0].byteLength },
  ];
  for (const view of json.bufferViews) view.buffer = 1;
  const gltf = testInfo.outputPath('spot_lowres.gltf');
  writeFileSync(gltf, JSON.stringify(json));

  const fromGlb = await uploadFile(page, meshPath('formats/spot_lowres.glb'));
  expect(fromGlb.ok).toBe(true);
  const glbPositions = await evaluateBulk(page, () => Array.from(window.anisoform.positions()));
  const fetched = [];
  page.on('request', (request) => fetched.push(request.url()));
  const outcome = await uploadFile(page, gltf);
  expect(outcome).toMatchObject({ ok: true, info: { vertices: 829, triangles: 1654 } });
  expect(await evaluateBulk(page, () => Array.from(window.anisoform.positions()))).toEqual(glbPositions);
  expect(fetched.filter((url) => url.startsWith('data:'))).toEqual([]);
  expect(pageErrors).toEqual([]);
});

test('a .gltf that keeps its geometry in another file is refused naming it, and nothing is fetched', async ({ page }, testInfo) => {
  const pageErrors = await openApp(page);
  // The smallest such file: one triangle whose positions are in ext.bin.
  const gltf = testInfo.outputPath('external-buffer.gltf');
  writeFileSync(gltf, JSON.stringify({
    asset: { version: '2.0' },
    buffers: [{ uri: 'ext.bin', byteLength: 36 }],
    bufferViews: [{ buffer: 0, byteLength: 36 }],
    accessors: [{ bufferView: 0, componentType: 5126, count: 3, type: 'VEC3', min: [0, 0, 0], max: [1, 1, 0] }],
    meshes: [{ primitives: [{ attributes: { POSITION: 0 } }] }],
    nodes: [{ mesh: 0 }],
    scenes: [{ nodes: [0] }],
    scene: 0,
  }));
  const fetched = [];
  page.on('request', (request) => fetched.push(request.url()));
  const outcome = await uploadFile(page, gltf);
  expect(outcome.ok).toBe(false);
  expect(outcome.message).toContain('external-buffer.gltf keeps its geometry in other files (ext.bin)');
  expect(outcome.message).toContain('The current mesh (spot_triangulated.obj) is unchanged');
  expect(fetched.filter((url) => url.endsWith('ext.bin'))).toEqual([]);
  expect(pageErrors).toEqual([]);
});

test('a mesh far from the origin for its size says that the view and GLB/STL files hold 32-bit floats', async ({ page }, testInfo) => {
  // Spot 1.7 units across, moved 1e6 away: it drew as a stepped, torn cow
  // (16 distinct x values) with no word of why.
  const pageErrors = await openApp(page);
  const far = testInfo.outputPath('spot_far.obj');
  writeFileSync(far, readFileSync(meshPath('formats/spot_lowres.obj'), 'utf8').split('\n')
    .map((line) => (line.startsWith('v ') ? `v ${line.slice(2).trim().split(/\s+/).map((x) => Number(x) + 1e6).join(' ')}` : line))
    .join('\n'));
  expect((await uploadFile(page, far)).ok).toBe(true);
  await expect(page.getByTestId('notice')).toContainText(
    'The mesh lies far from the origin for its size (1.00e+6 units away, 2.66 across): the view draws it in 32-bit floats');
  // At home, no such word.
  expect((await uploadFile(page, meshPath('formats/spot_lowres.obj'))).ok).toBe(true);
  await expect(page.getByTestId('notice').filter({ hasText: 'far from the origin' })).toBeHidden();
  expect(pageErrors).toEqual([]);
});
