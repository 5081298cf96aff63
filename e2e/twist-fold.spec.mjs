// tool-twist: a click on the mesh puts the twist's axis line through the
// clicked point (the panel shows it); the rate offered is a quarter turn over
// the height of each mesh loaded; an extreme amount applied from the panel
// folds triangles over, and the page warns about it until undo.
import { armChange, canvasCentre, expect, meshPath, openApp, selectUpperHalf, test, uploadFile } from './support.mjs';

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
    const field = page.getByRole('textbox', { name: `Origin point ${'xyz'[axis]}` });
    expect(Number(await field.inputValue())).toBeCloseTo(value, 5);
  }
  // A click is not an edit.
  expect(await page.evaluate(() => window.anisoform.undo())).toBe(false);
});

test('an extreme twist warns that triangles folded over; undo clears it', async ({ page }) => {
  await openApp(page);
  await page.getByTestId('tool-twist').click();
  const warning = page.getByTestId('warning');
  // The default amount (a quarter turn over Spot's height) folds nothing.
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

test('each mesh loaded offers a quarter turn over its height, which folds nothing on the armadillo', async ({ page }) => {
  const pageErrors = await openApp(page);
  await page.getByTestId('tool-twist').click();
  const rate = page.locator('#twist-degreesPerUnit');
  await expect(rate).toHaveValue('53'); // Spot: 1.69 units tall
  await rate.fill('90');
  await rate.press('Tab');
  // The armadillo is 151 units tall: 90 degrees per unit of Spot's would fold its upper half into shards.
  expect((await uploadFile(page, meshPath('closed/armadillo.off'))).ok).toBe(true);
  await expect(rate).toHaveValue('0.59');
  await selectUpperHalf(page);
  const committed = await armChange(page, 'positions');
  await page.getByTestId('apply-twist').click();
  await committed();
  const twist = await page.evaluate(() => window.anisoform.document().ops[0].op.transform.twist);
  expect(twist.degreesPerUnit).toBe(0.59);
  await expect(page.getByTestId('warning')).toBeHidden();
  expect(pageErrors).toEqual([]);
});
