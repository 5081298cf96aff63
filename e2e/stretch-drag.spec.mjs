// tool-stretch: a horizontal mouse drag on the mesh stretches it along the
// drag (the screen direction projected onto the surface): the extent along
// the camera's right axis grows, the extent along its up axis stays.
import { armChange, canvasCentre, evaluateBulk, expect, extentAlong, openApp, test } from './support.mjs';

test('a horizontal drag with the stretch tool stretches along the drag', async ({ page }) => {
  await openApp(page);
  await page.getByTestId('tool-stretch').click();
  const before = await evaluateBulk(page, () => Array.from(window.anisoform.positions()));
  const camera = await page.evaluate(() => window.anisoform.camera());
  // Rows of the view matrix (column-major elements) are the camera axes in world space.
  const right = [camera.view[0], camera.view[4], camera.view[8]];
  const up = [camera.view[1], camera.view[5], camera.view[9]];

  const centre = await canvasCentre(page);
  const committed = await armChange(page, 'positions');
  await page.mouse.move(...centre.page);
  await page.mouse.down();
  await page.mouse.move(centre.page[0] + 120, centre.page[1], { steps: 12 });
  await page.mouse.up();
  await committed();

  const after = await evaluateBulk(page, () => Array.from(window.anisoform.positions()));
  const growthRight = extentAlong(after, right) / extentAlong(before, right);
  const growthUp = extentAlong(after, up) / extentAlong(before, up);
  console.log(`stretch drag: right extent ×${growthRight.toFixed(3)}, up extent ×${growthUp.toFixed(3)}`);
  expect(growthRight).toBeGreaterThan(1.1);
  expect(Math.abs(growthUp - 1)).toBeLessThan(0.5 * (growthRight - 1));
  expect(await page.evaluate(() => window.anisoform.undo())).toBe(true);
});

test('the drag previews live, and Esc cancels it', async ({ page }) => {
  await openApp(page);
  await page.getByTestId('tool-stretch').click();
  const before = await evaluateBulk(page, () => Array.from(window.anisoform.positions()));
  const centre = await canvasCentre(page);
  await page.mouse.move(...centre.page);
  await page.mouse.down();
  await page.mouse.move(centre.page[0] + 100, centre.page[1], { steps: 10 });
  // A live preview shows in the status bar while the button is still down.
  await expect(page.getByTestId('status-solve')).toContainText('preview');
  await page.keyboard.press('Escape');
  await page.mouse.up();
  const after = await evaluateBulk(page, () => Array.from(window.anisoform.positions()));
  expect(after).toEqual(before);
  expect(await page.evaluate(() => window.anisoform.undo())).toBe(false);
});

test('during a drag, a select, an op change or an open through the API is refused; the drag commits on what it showed', async ({ page }) => {
  // select, removeOp, setOpEnabled and open were taken mid-drag (deform was
  // refused), and the released drag committed on the new region.
  await openApp(page);
  const region = { sphere: { center: [0, 0.3, 0.5], radius: 0.4 } };
  await page.evaluate(async (r) => {
    await window.anisoform.select(r);
    await window.anisoform.deform({ method: 'andefgrad', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: [1.1, 1] } });
  }, region);
  const selected = await evaluateBulk(page, () => Array.from(window.anisoform.selection()).flatMap((w, i) => (w > 0 ? [i] : [])));
  await page.getByTestId('tool-stretch').click();
  const centre = await canvasCentre(page);
  const committed = await armChange(page, 'positions');
  await page.mouse.move(...centre.page);
  await page.mouse.down();
  await page.mouse.move(centre.page[0] + 100, centre.page[1], { steps: 10 });
  await expect(page.getByTestId('status-solve')).toContainText('preview');
  const refusals = await page.evaluate(async () => {
    const api = window.anisoform;
    const opId = api.document().ops[0].id;
    const outcome = (promise) => promise.then(() => 'accepted', (error) => error.message);
    return [
      await outcome(api.select({ sphere: { center: [0, -0.6, 0], radius: 0.3 } })),
      await outcome(api.removeOp(opId)),
      await outcome(api.setOpEnabled(opId, false)),
      await outcome(api.setParameter(opId, { transform: { scale: [1.2, 1] } })),
      await outcome(api.open(api.document())),
    ];
  });
  await page.mouse.up();
  await committed();
  for (const message of refusals) expect(message).toContain('an interactive edit is in progress: finish the drag first');
  const document = await page.evaluate(() => window.anisoform.document());
  expect(document.ops.length).toBe(2);
  expect(document.ops[0].enabled ?? true).toBe(true);
  // The drag's region is the selection it previewed (as weights: the rule was made on the pose before the first op).
  const [{ region: dragged }] = document.regions.find((r) => r.name === document.ops[1].region).steps;
  expect(dragged.vertices).toEqual(selected);
});
