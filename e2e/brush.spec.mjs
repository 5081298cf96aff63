// The selection brush, with the real mouse on the canvas: the vertices under
// the cursor get selected, and only those.
import { canvasCentre, expect, openApp, test } from './support.mjs';

test('brushing with the mouse selects the vertices under the cursor', async ({ page }) => {
  await openApp(page);
  await page.getByTestId('tool-select').click();
  const centre = await canvasCentre(page);
  const hit = await page.evaluate((pixel) => window.anisoform.pick(pixel), centre.canvas);
  expect(hit).not.toBeNull();

  // A short stroke: press at the centre, move 6 px right, release.
  await page.mouse.move(...centre.page);
  await page.mouse.down();
  await page.mouse.move(centre.page[0] + 6, centre.page[1], { steps: 3 });
  await page.mouse.up();

  const result = await page.evaluate(({ point }) => {
    const positions = window.anisoform.positions();
    const weights = window.anisoform.selection();
    let count = 0;
    let farthest = 0;
    let nearest = -1;
    let nearestDistance = Infinity;
    for (let i = 0; i < weights.length; i++) {
      const distance = Math.hypot(
        positions[3 * i] - point[0],
        positions[3 * i + 1] - point[1],
        positions[3 * i + 2] - point[2],
      );
      if (distance < nearestDistance) {
        nearestDistance = distance;
        nearest = i;
      }
      if (weights[i] > 0) {
        count++;
        farthest = Math.max(farthest, distance);
      }
    }
    const { min, max } = (() => {
      const lo = [Infinity, Infinity, Infinity];
      const hi = [-Infinity, -Infinity, -Infinity];
      for (let i = 0; i < positions.length; i++) {
        lo[i % 3] = Math.min(lo[i % 3], positions[i]);
        hi[i % 3] = Math.max(hi[i % 3], positions[i]);
      }
      return { min: lo, max: hi };
    })();
    const diagonal = Math.hypot(max[0] - min[0], max[1] - min[1], max[2] - min[2]);
    return { count, farthest, diagonal, nearestWeight: weights[nearest], total: weights.length };
  }, hit);

  expect(result.count).toBeGreaterThan(10);
  expect(result.count).toBeLessThan(result.total / 2);
  expect(result.nearestWeight).toBe(1);
  // Default brush radius is 8 % of the diagonal; the 6 px stroke adds a little.
  expect(result.farthest).toBeLessThan(0.08 * result.diagonal * 1.5);

  // The stroke is one undo step.
  expect(await page.evaluate(() => window.anisoform.undo())).toBe(true);
  expect(await page.evaluate(() => window.anisoform.selection().some((w) => w > 0))).toBe(false);
});

// CSS zoom on the page (a page that scales its content, or a user style):
// the canvas's client rect is zoomed, its clientWidth is not. The pointer's
// offset was used as canvas pixels as it was, so a press at a quarter of the
// view picked and painted at its middle, and the outline was drawn at twice
// the distance from the view's corner.
test('under CSS zoom 2 the brush paints and draws its outline where the pointer is', async ({ page }) => {
  const pageErrors = await openApp(page);
  await page.getByTestId('tool-select').click();
  await page.evaluate(() => (document.documentElement.style.zoom = '2'));
  try {
    const rect = await page.getByTestId('viewport').evaluate((canvas) => {
      const box = canvas.getBoundingClientRect();
      return { left: box.left, top: box.top, width: box.width, height: box.height };
    });
    const stroke = async (x, y) => {
      await page.mouse.move(x, y);
      await page.mouse.down();
      await page.mouse.move(x + 4, y, { steps: 2 });
      await page.mouse.up();
    };
    // Empty background a quarter into the view (the old mapping hit the cow in the middle).
    const quarter = [rect.left + rect.width / 4, rect.top + rect.height / 4];
    await stroke(...quarter);
    expect(await page.evaluate(() => window.anisoform.selection().some((w) => w > 0))).toBe(false);
    // The middle of the view: the cow, and the outline is centred on the pointer.
    const middle = [rect.left + rect.width / 2, rect.top + rect.height / 2];
    await page.mouse.move(middle[0] - 3, middle[1]);
    await page.mouse.move(...middle);
    const outline = await page.locator('.brush-cursor').evaluate((element) => {
      const box = element.getBoundingClientRect();
      return [box.left + box.width / 2, box.top + box.height / 2];
    });
    expect(outline[0]).toBeCloseTo(middle[0], 0);
    expect(outline[1]).toBeCloseTo(middle[1], 0);
    await stroke(...middle);
    await expect.poll(() => page.evaluate(() => window.anisoform.selection().some((w) => w > 0))).toBe(true);
  } finally {
    await page.evaluate(() => (document.documentElement.style.zoom = ''));
  }
  expect(pageErrors).toEqual([]);
});
