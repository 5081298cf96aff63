// Flatten mode in an 800 × 600 window, where the 3D view and the pattern
// pane share 520 px: the pattern header's controls stay inside the window
// (Fit was pushed past its right edge), and a long warning over the 3D view
// shows three lines and More instead of covering the view.
import { expect, meshPath, openApp, test, uploadFile } from './support.mjs';

test.use({ viewport: { width: 800, height: 600 } });

test('800 px, Flatten: the pattern header fits, a long warning over the narrow 3D view folds to three lines and More', async ({ page }) => {
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
