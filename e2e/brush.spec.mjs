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
