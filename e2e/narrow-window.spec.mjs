// Windows just wide enough for the side panel beside the view:
// - Flatten mode in an 800 × 600 window, where the 3D view and the pattern
//   pane share 520 px: the pattern header's controls stay inside the window
//   (Fit was pushed past its right edge), and a long warning over the 3D view
//   shows three lines and More instead of covering the view;
// - a solve's progress in a 900 px window: the status bar shows it whole.
import { expect, meshPath, openApp, startLongCommit, test, uploadFile } from './support.mjs';

test('800 px, Flatten: the pattern header fits, a long warning over the narrow 3D view folds to three lines and More', async ({ page }) => {
  await page.setViewportSize({ width: 800, height: 600 });
  const pageErrors = await openApp(page);
  // The hand is no developable patch: flattening it warns at length.
  expect((await uploadFile(page, meshPath('open/hand_lowres.obj'))).ok).toBe(true);
  await page.getByTestId('mode-flatten').click();
  await page.getByTestId('flatten-run').click();
  const warning = page.getByTestId('warning');
  await expect(warning).toContainText('does not flatten as one piece');

  const right = (locator) => locator.evaluate((element) => element.getBoundingClientRect().right);
  const header = page.locator('.pattern-header');
  for (const control of [header.getByRole('button', { name: 'Fit' }), header.getByRole('combobox')]) {
    expect(await right(control)).toBeLessThanOrEqual(800);
  }
  const more = warning.getByTestId('message-more');
  await expect(more).toBeVisible();
  const viewHeight = await page.getByTestId('viewport').evaluate((element) => element.getBoundingClientRect().height);
  const folded = await warning.evaluate((element) => element.getBoundingClientRect().height);
  expect(folded).toBeLessThan(0.4 * viewHeight);
  await more.click();
  await expect(more).toHaveText('Less');
  expect(await warning.evaluate((element) => element.getBoundingClientRect().height)).toBeGreaterThan(folded);
  expect(pageErrors).toEqual([]);
});

test("900 px: a solve's progress, percentage and Cancel show whole in the status bar, and the mesh's counts too", async ({ page }) => {
  await page.setViewportSize({ width: 900, height: 600 });
  const pageErrors = await openApp(page);
  await startLongCommit(page);
  await expect(page.getByTestId('progress')).toContainText(/Solving \d+ %/, { timeout: 30_000 });
  const cut = await page.evaluate(() => [...document.querySelectorAll('.status-bar .status-item, .status-bar .status-item *')]
    .filter((element) => element.getClientRects().length > 0 && element.scrollWidth > element.clientWidth + 1)
    .map((element) => `${element.dataset.testid ?? element.className}: "${element.textContent}" (${element.scrollWidth} > ${element.clientWidth} px)`));
  expect(cut).toEqual([]);
  await expect(page.getByTestId('status-mesh')).toHaveText(/^26,002 vertices · 52,000 triangles/);
  await expect(page.getByTestId('cancel-solve')).toBeVisible();
  await page.getByTestId('cancel-solve').click();
  expect(await page.evaluate(() => window.__long)).toBe('cancelled');
  // The last solve's figures are back once it has ended.
  await expect(page.getByTestId('status-solve')).toBeVisible();
  expect(pageErrors).toEqual([]);
});
