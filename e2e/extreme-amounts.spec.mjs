// Issue 9 item 8: the amount fields show the value that is used, and an
// extreme amount that folds triangles over says how many, for the live
// preview and for the committed edit.
import { armChange, canvasCentre, evaluateBulk, expect, openApp, saveScreenshot, test } from './support.mjs';

test('a typed out-of-range amount is shown as used: the core refuses it by name, a panel bound clamps at once', async ({ page }) => {
  const pageErrors = await openApp(page);
  await page.getByTestId('tool-stretch').click();
  await page.locator('#direction-source').selectOption('global');
  const before = await evaluateBulk(page, () => Array.from(window.anisoform.positions()));

  const along = page.locator('#stretch-along');
  await along.fill('-3');
  await along.press('Enter');
  await expect(along).toHaveValue('-3');
  await page.getByTestId('apply-stretch').click();
  const error = page.getByTestId('error');
  await expect(error).toBeVisible();
  await expect(error).toContainText('-3');
  await expect(error).toContainText(/must be positive/);
  await expect(along).toHaveValue('-3');
  expect(await evaluateBulk(page, () => Array.from(window.anisoform.positions()))).toEqual(before);

  // The brush radius is the panel's own bound (0.5 .. 100 %): the field shows the clamped value while still focused.
  await page.getByTestId('tool-select').click();
  const radius = page.locator('#brush-radiusPercent');
  await radius.fill('500');
  await radius.press('Enter');
  await expect(radius).toBeFocused();
  await expect(radius).toHaveValue('100');
  expect(pageErrors).toEqual([]);
});

test('Stretch 20 from the panel warns how many triangles folded over, as the core counted them', async ({ page }) => {
  const pageErrors = await openApp(page);
  const centre = await canvasCentre(page);
  const hit = await page.evaluate((pixel) => window.anisoform.pick(pixel), centre.canvas);
  await page.evaluate((point) => window.anisoform.select({ sphere: { center: point, radius: 0.3 } }, { falloff: 0.1 }), hit.point);
  await page.getByTestId('tool-stretch').click();
  await page.locator('#direction-source').selectOption('global');
  await page.locator('#stretch-along').fill('20');
  await page.locator('#stretch-along').press('Enter');
  const committed = await armChange(page, 'positions');
  await page.getByTestId('apply-stretch').click();
  await committed();
  const warning = page.getByTestId('warning');
  await expect(warning).toBeVisible();
  await expect(warning).toContainText(/^\d+ triangles? folded over: reduce the amount or the falloff/);
  const shown = Number((await warning.textContent()).match(/^\d+/)[0]);
  await saveScreenshot(page, 'stretch-20-folds');

  // The same op through the API: the core's count is the one shown.
  const counted = await page.evaluate(async () => {
    const api = window.anisoform;
    await api.undo();
    const result = await api.deform({ method: 'anarap', direction: { type: 'global', vector: [1, 0, 0] }, transform: { scale: [20, 1] }, maxIterations: 50 });
    return result.inverted;
  });
  expect(shown).toBeGreaterThan(0);
  expect(counted).toBe(shown);
  expect(pageErrors).toEqual([]);
});

test('a live drag that folds triangles warns while it lasts', async ({ page }) => {
  const pageErrors = await openApp(page);
  const centre = await canvasCentre(page);
  const hit = await page.evaluate((pixel) => window.anisoform.pick(pixel), centre.canvas);
  await page.evaluate((point) => window.anisoform.select({ sphere: { center: point, radius: 0.15 } }), hit.point);
  await page.getByTestId('tool-stretch').click();
  // The warning is recorded as the page shows it: the settling iterations
  // after the pointer stops unfold this drag's triangles within a few hundred
  // ms, and a poll of the banner could miss so short a warning on a busy host.
  await page.evaluate(() => {
    const banner = document.querySelector('[data-testid=warning]');
    window.__warnings = [];
    new MutationObserver(() => {
      if (!banner.hidden) window.__warnings.push(banner.textContent);
    }).observe(banner, { attributes: true, childList: true, subtree: true, characterData: true });
  });
  await page.mouse.move(...centre.page);
  await page.mouse.down();
  await page.mouse.move(centre.page[0] + 400, centre.page[1] + 20, { steps: 16 });
  await expect.poll(() => page.evaluate(() => window.__warnings.length), { timeout: 20_000 }).toBeGreaterThan(0);
  expect(await page.evaluate(() => window.__warnings[0])).toMatch(/\d+ triangles? folded over/);
  const committed = await armChange(page, 'positions');
  await page.mouse.up();
  await committed();
  expect(pageErrors).toEqual([]);
});
