// A drag's live shape settles while the pointer rests (editor/gesture-
// controller.js): the edit goes on iterating, so that the shape shown comes
// close to the one the release commits. Before, a drag's previews were an
// iteration each and stopped with the pointer: on Spot a shear's last live
// shape stayed where the moves had left it until the release.
import { armChange, canvasCentre, evaluateBulk, expect, openApp, test } from './support.mjs';

// The largest distance of a live shape's vertices from the committed ones,
// as a fraction of the committed shape's bounding-box diagonal.
function distanceFrom(final) {
  const low = [Infinity, Infinity, Infinity];
  const high = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < final.length; i++) {
    low[i % 3] = Math.min(low[i % 3], final[i]);
    high[i % 3] = Math.max(high[i % 3], final[i]);
  }
  const diagonal = Math.hypot(...high.map((h, k) => h - low[k]));
  return (shape) => {
    let max = 0;
    for (let i = 0; i < final.length; i += 3) {
      max = Math.max(max, Math.hypot(shape[i] - final[i], shape[i + 1] - final[i + 1], shape[i + 2] - final[i + 2]));
    }
    return max / diagonal;
  };
}

test('a resting pointer keeps the live shape iterating towards the committed one', async ({ page }) => {
  await openApp(page);
  await page.getByTestId('tool-shear').click();
  await page.evaluate(() => {
    const shapes = [];
    window.__shapes = shapes;
    window.anisoform.on('positions', ({ positions, live }) => {
      if (live) shapes.push({ at: performance.now(), positions: Array.from(positions) });
    });
  });
  const centre = await canvasCentre(page);
  const committed = await armChange(page, 'positions');
  await page.mouse.move(...centre.page);
  await page.mouse.down();
  await page.mouse.move(centre.page[0] + 40, centre.page[1] - 90, { steps: 8 });
  const rested = await page.evaluate(() => performance.now());
  await page.waitForTimeout(1500);
  const whileResting = await page.evaluate((since) => window.__shapes.filter((s) => s.at > since).length, rested);
  await page.mouse.up();
  await committed();

  const { after, final } = await evaluateBulk(page, (since) => ({
    after: window.__shapes.filter((s) => s.at > since).map((s) => s.positions),
    final: Array.from(window.anisoform.positions()),
  }), rested);
  const distance = distanceFrom(final);
  const first = distance(after[0]);
  const last = distance(after.at(-1));
  console.log(`settling: ${whileResting} live shapes in 1.5 s at rest; the first after the moves `
    + `${(100 * first).toFixed(2)} % of the diagonal from the committed shape, the last ${(100 * last).toFixed(3)} %`);
  expect(whileResting).toBeGreaterThanOrEqual(3);
  expect(after.length).toBeGreaterThanOrEqual(whileResting);
  // The moves left the shape visibly short of the committed one; resting
  // brought it most of the way.
  expect(first).toBeGreaterThan(1e-3);
  expect(last).toBeLessThan(0.5 * first);
  expect(await page.evaluate(() => window.anisoform.undo())).toBe(true);
});

test("a slider resting on the last op's value keeps its live shape iterating towards the committed one", async ({ page }) => {
  await openApp(page);
  const { shapes, afterValue, final } = await evaluateBulk(page, async () => {
    const api = window.anisoform;
    await api.select({ box: { min: [-1, 0.2, -1], max: [1, 1, 1] } });
    await api.deform({ method: 'anarap', direction: { type: 'global', vector: [1, 0, 0] }, transform: { shear: 0.1 } });
    const opId = api.document().ops[0].id;
    const live = [];
    const off = api.on('positions', ({ positions, live: isLive }) => {
      if (isLive) live.push(Array.from(positions));
    });
    // A slider let go of at 0.5 after one move there, resting for 1.5 s.
    await api.setParameter(opId, { transform: { shear: 0.5 } }, { preview: true });
    const count = live.length;
    await new Promise((resolve) => setTimeout(resolve, 1500));
    off();
    await api.setParameter(opId, { transform: { shear: 0.5 } });
    return { shapes: live, afterValue: count, final: Array.from(api.positions()) };
  });
  const distance = distanceFrom(final);
  const first = distance(shapes[afterValue - 1]);
  const last = distance(shapes.at(-1));
  console.log(`slider settling: ${shapes.length - afterValue} live shapes at rest; the value's own preview `
    + `${(100 * first).toFixed(2)} % of the diagonal from the committed shape, the last ${(100 * last).toFixed(3)} %`);
  expect(shapes.length - afterValue).toBeGreaterThanOrEqual(3);
  expect(first).toBeGreaterThan(1e-3);
  expect(last).toBeLessThan(0.5 * first);
});
