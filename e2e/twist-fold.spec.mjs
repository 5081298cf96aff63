// tool-twist: a click on the mesh puts the twist's axis line through the
// clicked point (the panel shows it); an extreme amount applied from the
// panel folds triangles over, and the page warns about it until undo.
import { armChange, canvasCentre, expect, openApp, test } from './support.mjs';

test('a click with the twist tool sets the origin to the clicked point', async ({ page }) => {
  await openApp(page);
  await page.getByTestId('tool-twist').click();
  const origin = page.locator('#twist-origin');
  await expect(origin).toHaveValue('centroid');
  const centre = await canvasCentre(page);
  const hit = await page.evaluate((pixel) => window.anisoform.pick(pixel), centre.canvas);
  expect(hit).not.toBeNull();
  await page.mouse.click(...centre.page);
  await expect(origin).toHaveValue('point');
  for (const [axis, value] of hit.point.entries()) {
    const field = page.getByRole('spinbutton', { name: `Origin point ${'xyz'[axis]}` });
    expect(Number(await field.inputValue())).toBeCloseTo(value, 5);
  }
  // A click is not an edit.
  expect(await page.evaluate(() => window.anisoform.undo())).toBe(false);
});

test('an extreme twist warns that triangles folded over; undo clears it', async ({ page }) => {
  await openApp(page);
  await page.getByTestId('tool-twist').click();
  const warning = page.getByTestId('warning');
  // Apply needs a direction source that has a direction without a drag.
  await page.locator('#direction-source').selectOption('global');
  // The default amount (90°/unit) folds nothing.
  let committed = await armChange(page, 'positions');
  await page.getByTestId('apply-twist').click();
  await committed();
  await expect(warning).toBeHidden();

  await page.locator('#twist-degreesPerUnit').fill('12000');  // near the largest valid twist on Spot (limits.h: 36000 degrees over the diagonal)
  await page.locator('#twist-degreesPerUnit').press('Enter');
  committed = await armChange(page, 'positions');
  await page.getByTestId('apply-twist').click();
  await committed();
  await expect(warning).toBeVisible();
  await expect(warning).toContainText(/\d+ triangles? folded over: reduce the amount or the falloff/);
  const count = Number((await warning.textContent()).match(/\d+/)[0]);
  expect(count).toBeGreaterThan(0);
  expect(await page.evaluate(() => window.anisoform.undo())).toBe(true);
  await expect(warning).toBeHidden();
});
