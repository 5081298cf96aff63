// The distortion heat map shows the core's numbers (Session.distortion in the
// worker) and follows the mesh: live-preview frames bring their values along,
// a commit too, and undo asks the worker again. Red = grown (distortion_heatmap.glsl).
import { armChange, canvasCentre, countPixels, expect, openApp, test } from './support.mjs';

// Pixels of the viewport that are clearly red (the heat map's "grown").
const redPixels = async (page) => (await countPixels(page, 'viewport', { red: true })).lit;

test('the stretch heat map colours a live drag, its commit, and clears on undo', async ({ page }) => {
  const pageErrors = await openApp(page);
  await page.locator('#display-heatMap').selectOption('stretch');
  await page.getByTestId('tool-stretch').click();
  const unchanged = await redPixels(page);

  const centre = await canvasCentre(page);
  const committed = await armChange(page, 'positions');
  await page.mouse.move(...centre.page);
  await page.mouse.down();
  await page.mouse.move(centre.page[0] + 150, centre.page[1], { steps: 12 });
  await expect(page.getByTestId('status-solve')).toContainText('preview');
  await expect.poll(() => redPixels(page), { timeout: 10_000 }).toBeGreaterThan(unchanged + 500);
  await page.mouse.up();
  await committed();
  await expect.poll(() => redPixels(page), { timeout: 10_000 }).toBeGreaterThan(unchanged + 500);

  expect(await page.evaluate(() => window.anisoform.undo())).toBe(true);
  await expect.poll(() => redPixels(page), { timeout: 10_000 }).toBeLessThan(unchanged + 50);
  await expect(page.getByTestId('error')).toBeHidden();
  expect(pageErrors).toEqual([]);
});

test('the compression error heat map before any flattening says there is no pattern yet, with no scale', async ({ page }) => {
  const pageErrors = await openApp(page);
  await page.locator('#display-heatMap').selectOption('compression');
  const legend = page.getByTestId('heatmap-legend');
  await expect(legend).toBeVisible();
  await expect(page.getByTestId('heatmap-legend-range')).toHaveText(/^No pattern yet: flatten a patch/);
  await expect(page.getByTestId('heatmap-legend-values')).toBeEmpty();
  // Once flattened, the scale and its range are shown.
  await page.evaluate(async () => {
    await window.anisoform.select({ sphere: { center: [0, 0.2, 0.4], radius: 0.3 } });
    await window.anisoform.flatten({ compress: 0.9, direction: { type: 'global', vector: [1, 0, 0] }, patch: 'selection' });
  });
  await expect(page.getByTestId('heatmap-legend-range')).toHaveText(/Range adapted|Fixed range/);
  await expect(page.getByTestId('heatmap-legend-values').locator('span')).toHaveCount(3);
  expect(pageErrors).toEqual([]);
});
