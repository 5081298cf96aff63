// The words of the banners: a load error names the file once and keeps
// sentences apart, the core's messages read as English ("not an OBJ mesh"),
// a notice is sentences with counts and first elements instead of a wall of
// indices (the full list on demand), and a failed load does not leave the
// old mesh's notice standing under its error.
import { expect, meshPath, openApp, test, uploadFile } from './support.mjs';

const occurrences = (text, part) => text.split(part).length - 1;
// The notice's own sentence, without the collapsed details list.
const noticeSummary = (page) =>
  page.getByTestId('notice').evaluate((element) => element.querySelector('span').firstChild.textContent);

test('a load error names the file once, in plain English', async ({ page }) => {
  await openApp(page);
  const outcome = await uploadFile(page, meshPath('malformed/empty.obj'));
  expect(outcome.ok).toBe(false);
  expect(outcome.message).toBe(
    'Could not load empty.obj: file is empty (0 bytes): not an OBJ mesh. The current mesh (spot_triangulated.obj) is unchanged.',
  );
  const text = (await page.getByTestId('error').textContent()) ?? '';
  expect(occurrences(text, 'empty.obj')).toBe(1);
  expect(text).toContain('not an OBJ mesh.');
});

test('the problems of a mesh that cannot be edited are kept apart', async ({ page }) => {
  await openApp(page);
  const outcome = await uploadFile(page, meshPath('malformed/empty_mesh_header_only.off'));
  expect(outcome.ok).toBe(false);
  expect(outcome.message).toContain('the mesh has no vertices; the mesh has no triangles.');
  expect(occurrences(outcome.message, 'empty_mesh_header_only.off')).toBe(1);
  await expect(page.getByTestId('error')).toContainText('no vertices; the mesh has no triangles');
});

test('a notice is sentences, and a failed load clears the old one', async ({ page }) => {
  const pageErrors = await openApp(page);
  expect((await uploadFile(page, meshPath('malformed/testmixed.obj'))).ok).toBe(true);
  await expect(page.getByTestId('notice')).toBeVisible();
  expect(await noticeSummary(page)).toBe(
    'Skipped 12 point, line or curve elements (p, l, curv, surf). Triangulated 6 polygons with more than 3 corners.',
  );
  // Its dismiss button is named in words, not "×".
  const dismiss = page.getByTestId('notice').getByRole('button', { name: 'Dismiss message', exact: true });
  await expect(dismiss).toBeVisible();

  expect((await uploadFile(page, meshPath('malformed/empty.obj'))).ok).toBe(false);
  await expect(page.getByTestId('error')).toContainText('The current mesh (testmixed.obj) is unchanged.');
  await expect(page.getByTestId('notice')).toBeHidden();
  expect(pageErrors).toEqual([]);
});

// An open surface is no problem: the status bar says it, no banner covers the view.
test('an open mesh with nothing to repair loads without a notice; the status bar says it is open', async ({ page }) => {
  const pageErrors = await openApp(page);
  const status = page.getByTestId('status-mesh');
  await expect(status).toHaveAttribute('title', 'Closed surface');
  expect((await uploadFile(page, meshPath('open/human_woman_torso_front_patch.obj'))).ok).toBe(true);
  await expect(status).toHaveText('531 vertices · 972 triangles · open');
  await expect(status).toHaveAttribute('title', 'Open surface: 1 boundary loop');
  await expect(page.getByTestId('notice')).toBeHidden();
  // With something to say, the notice says that only.
  expect((await uploadFile(page, meshPath('open/stanford-bunny.obj'))).ok).toBe(true);
  await expect(status).toHaveAttribute('title', 'Open surface: 5 boundary loops');
  await expect(page.getByTestId('notice')).toBeVisible();
  expect(await noticeSummary(page)).not.toContain('boundary loop');
  expect(pageErrors).toEqual([]);
});

test('a repair notice counts problems and lists them on demand', async ({ page }) => {
  await openApp(page);
  expect((await uploadFile(page, meshPath('malformed/Spider_binary.stl'))).ok).toBe(true);
  const notice = page.getByTestId('notice');
  await expect(notice).toBeVisible();
  const summary = await noticeSummary(page);
  expect(summary).toContain('56 triangles using a vertex twice (first: faces 924,');
  expect(summary).toContain('16 non-manifold edges (first at faces 933,');
  // No face lists of single problems in the summary: those are the details.
  expect(summary).not.toContain('is shared by 6 faces');
  expect(summary.length).toBeLessThan(700);

  const details = notice.getByTestId('notice-details');
  const fullLine = details.getByText('Edge (487, 491) is shared by 6 faces (926, 927, 927, 932, 932, 933); an edge may border at most 2.');
  await expect(fullLine).toBeHidden();
  await details.locator('summary').click();
  await expect(fullLine).toBeVisible();
});

test('a refused selection reaches the banner and rejects with the core code, the selection unchanged', async ({ page }) => {
  await openApp(page);
  const outcome = await page.evaluate(async () => {
    const api = window.anisoform;
    const before = api.selection();
    try {
      await api.select({ sphere: { center: [0, 0, 0], radius: -1 } });
      return { rejected: false };
    } catch (error) {
      const after = api.selection();
      return { rejected: true, code: error.code, message: error.message, same: after.every((w, i) => w === before[i]) };
    }
  });
  expect(outcome).toMatchObject({ rejected: true, code: 'bad-parameter', same: true });
  expect(outcome.message).toContain('The selection was not changed');
  expect(outcome.message).toContain('radius');
  await expect(page.getByTestId('error')).toContainText('The selection was not changed');
});

test('an edit refused stays on the banner until a later edit is solved', async ({ page }) => {
  const pageErrors = await openApp(page);
  await page.getByTestId('select-all').click();
  await page.locator('#direction-source').selectOption('screen');
  await page.getByTestId('tool-stretch').click();
  await page.getByTestId('apply-stretch').click();
  const error = page.getByTestId('error');
  await expect(error).toContainText('screen');
  // A selection leaves it up; a solved edit clears it.
  await page.getByTestId('select-all').click();
  await expect(error).toBeVisible();
  await page.locator('#direction-source').selectOption('global');
  await page.getByTestId('apply-stretch').click();
  await expect.poll(() => page.evaluate(() => window.anisoform.document().ops.length)).toBe(1);
  await expect(error).toBeHidden();
  expect(pageErrors).toEqual([]);
});
