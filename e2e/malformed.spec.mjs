// Every file of shared/meshes/malformed gets a message in plain words and
// never breaks the page:
//   'rejected'  the file cannot be edited: [data-testid=error] says why
//               (naming the line, face or vertex), and the mesh loaded
//               before stays, bitwise;
//   'notice'    the file loads, and [data-testid=notice] says what the reader
//               repaired (the soup welded, polygons triangulated, elements
//               skipped) or what the mesh check found that editing works
//               through (zero-area or flipped triangles, non-manifold edges,
//               separate parts);
//   'open'      the file loads with nothing to repair but a crack: no banner
//               over the view, the status bar says the surface is open and
//               its title how many boundary loops it has.
import { readdirSync } from 'node:fs';
import { evaluateBulk, expect, meshesDir, meshPath, openApp, test, uploadFile } from './support.mjs';

const EXPECTED = {
  'Spider_binary.stl': 'notice',
  'bad_degenerate_faces.obj': 'notice',
  'bad_flipped_faces.obj': 'notice',
  'bad_index_out_of_range.obj': 'rejected',
  'bad_index_out_of_range.off': 'rejected',
  'bad_nan_coordinate.obj': 'rejected',
  'bad_nonmanifold_edge.obj': 'notice',
  'bad_triangle_soup.obj': 'notice',
  'boxNotManifold.glb': 'open',
  'boxNotManifold.obj': 'open',
  'box_UTF16BE.obj': 'notice',
  'box_without_lineending.obj': 'notice',
  'degtri_sliding.off': 'notice',
  'empty.obj': 'rejected',
  'empty.off': 'rejected',
  'empty.ply': 'rejected',
  'empty.stl': 'rejected',
  'empty_mesh_header_only.off': 'rejected',
  'empty_mesh_header_only.ply': 'rejected',
  'empty_mesh_zero_triangles.stl': 'rejected',
  'multi_component.obj': 'notice',
  'number_formats.obj': 'rejected',
  'openscad-nonmanifold-crash.obj': 'notice',
  'testmixed.obj': 'notice',
  'truncated_binary.ply': 'rejected',
  'truncated_binary.stl': 'rejected',
};

const files = readdirSync(`${meshesDir}/malformed`);

test('every file in malformed/ has an expected outcome', () => {
  expect(files.sort()).toEqual(Object.keys(EXPECTED).sort());
});

test.describe('loading every malformed file', () => {
  let page;
  const reference = 'formats/spot_lowres.obj';
  test.beforeAll(async ({ browser }) => {
    page = await browser.newPage();
    await openApp(page);
  });
  test.afterAll(() => page.close());

  for (const [name, expected] of Object.entries(EXPECTED)) {
    test(`${name}: ${expected}`, async () => {
      // Start each case from the same known mesh.
      expect(await uploadFile(page, meshPath(reference))).toMatchObject({ ok: true });
      const before = await evaluateBulk(page, () => Array.from(window.anisoform.positions()));

      const outcome = await uploadFile(page, meshPath(`malformed/${name}`));
      if (expected === 'rejected') {
        expect(outcome.ok, `${name} should be rejected`).toBe(false);
        const error = page.getByTestId('error');
        await expect(error).toBeVisible();
        await expect(error).toContainText(name);
        await expect(error).toContainText('unchanged');
        const after = await evaluateBulk(page, () => Array.from(window.anisoform.positions()));
        expect(after).toEqual(before);
        expect(await page.evaluate(() => window.anisoform.info().vertices)).toBe(829);
      } else if (expected === 'open') {
        expect(outcome, `${name} should load`).toMatchObject({ ok: true });
        await expect(page.getByTestId('error')).toBeHidden();
        await expect(page.getByTestId('notice')).toBeHidden();
        await expect(page.getByTestId('status-mesh')).toHaveText(/ · open$/);
        await expect(page.getByTestId('status-mesh')).toHaveAttribute('title', 'Open surface: 1 boundary loop');
      } else {
        expect(outcome, `${name} should load`).toMatchObject({ ok: true });
        await expect(page.getByTestId('error')).toBeHidden();
        const notice = page.getByTestId('notice');
        await expect(notice).toBeVisible();
        const text = (await notice.textContent()) ?? '';
        expect(text.length).toBeGreaterThan(10);
        test.info().annotations.push({ type: 'notice', description: text });
      }
    });
  }
});
