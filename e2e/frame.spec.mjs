// Re-framing the 3D view: the Frame button, the F and Home keys and
// anisoform.frame() fit the camera back to the whole mesh after a zoom; a
// double-click on the mesh orbits around the clicked point; the Deform /
// Flatten switch, which halves the viewport, keeps a fitted mesh in view.
import { canvasCentre, expect, openApp, test } from './support.mjs';

/** Camera distance to its orbit target. */
const distance = (page) => page.evaluate(() => {
  const { position, target } = window.anisoform.camera();
  return Math.hypot(position[0] - target[0], position[1] - target[1], position[2] - target[2]);
});

/** Largest |x| or |y| in NDC of the mesh's bounding-box corners: <= 1 means all of it is on the canvas. */
const projectedExtent = (page) => page.evaluate(() => {
  const positions = window.anisoform.positions();
  const min = [Infinity, Infinity, Infinity];
  const max = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < positions.length; i++) {
    min[i % 3] = Math.min(min[i % 3], positions[i]);
    max[i % 3] = Math.max(max[i % 3], positions[i]);
  }
  const { view, projection } = window.anisoform.camera();
  const apply = (m, v) => [0, 1, 2, 3].map((r) => m[r] * v[0] + m[4 + r] * v[1] + m[8 + r] * v[2] + m[12 + r] * v[3]);
  let extent = 0;
  for (let corner = 0; corner < 8; corner++) {
    const point = [0, 1, 2].map((k) => (corner >> k) & 1 ? max[k] : min[k]);
    const clip = apply(projection, apply(view, [...point, 1]));
    extent = Math.max(extent, Math.abs(clip[0] / clip[3]), Math.abs(clip[1] / clip[3]));
  }
  return extent;
});

async function zoomIn(page) {
  const before = await distance(page);
  const { page: [x, y] } = await canvasCentre(page);
  await page.mouse.move(x, y);
  for (let i = 0; i < 8; i++) await page.mouse.wheel(0, -400);
  await expect.poll(() => distance(page)).toBeLessThan(before * 0.5);
}

test('F, Home, the Frame button and anisoform.frame() fit the mesh again after a wheel zoom', async ({ page }) => {
  const pageErrors = await openApp(page);
  const fitted = await distance(page);
  expect(await projectedExtent(page)).toBeLessThanOrEqual(1);

  const button = page.getByRole('button', { name: 'Frame mesh' });
  await expect(button).toHaveAttribute('title', /\bF\b.*Home/);

  for (const refit of [
    () => page.keyboard.press('f'),
    () => page.keyboard.press('Home'),
    () => button.click(),
    () => page.evaluate(() => window.anisoform.frame()),
  ]) {
    await zoomIn(page);
    await refit();
    await expect.poll(async () => Math.abs((await distance(page)) / fitted - 1)).toBeLessThan(0.01);
    expect(await projectedExtent(page)).toBeLessThanOrEqual(1);
  }

  // Not while typing in a field: F belongs to the field there.
  await zoomIn(page);
  const zoomed = await distance(page);
  await page.locator('input[inputmode="decimal"]').first().focus();
  await page.keyboard.press('f');
  await page.keyboard.press('Home');
  expect(await distance(page)).toBeCloseTo(zoomed, 6);
  expect(pageErrors).toEqual([]);
});

test('double-clicking the mesh orbits around the clicked point from the same distance', async ({ page }) => {
  const pageErrors = await openApp(page);
  const before = await distance(page);
  const { page: [x, y], canvas: [cx, cy] } = await canvasCentre(page);
  const hit = await page.evaluate(([px, py]) => window.anisoform.pick([px, py]), [cx + 20, cy + 10]);
  expect(hit).not.toBeNull();
  await page.mouse.dblclick(x + 20, y + 10);
  await expect.poll(() => page.evaluate(() => window.anisoform.camera().target)).toEqual(hit.point.map((v) => expect.closeTo(v, 5)));
  expect(Math.abs((await distance(page)) / before - 1)).toBeLessThan(1e-4);
  expect(pageErrors).toEqual([]);
});

test('switching to Flatten and back keeps the whole fitted mesh in view', async ({ page }) => {
  const pageErrors = await openApp(page);
  await zoomIn(page);
  await page.keyboard.press('f');
  const deformWidth = (await canvasCentre(page)).box.width;

  await page.getByTestId('mode-flatten').click();
  await expect.poll(async () => (await canvasCentre(page)).box.width).toBeLessThan(deformWidth * 0.75);
  await expect.poll(() => projectedExtent(page)).toBeLessThanOrEqual(1);

  await page.getByTestId('mode-deform').click();
  await expect.poll(async () => (await canvasCentre(page)).box.width).toBeCloseTo(deformWidth, 0);
  await expect.poll(() => projectedExtent(page)).toBeLessThanOrEqual(1);
  // Back at the Deform size the fit is the first one again, not a smaller mesh.
  expect(await projectedExtent(page)).toBeGreaterThan(0.5);
  expect(pageErrors).toEqual([]);
});
