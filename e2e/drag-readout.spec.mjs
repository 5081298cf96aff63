// The drag readout: while a Stretch / Thicken / Shear / Rotate / Twist drag
// is on, the amount shows beside the pointer (×1.35, 20°); it is the amount
// the edit commits (the op's transform in api.document()), and it goes away
// when the drag ends or Esc cancels it.
import { saveScreenshot } from './artifacts.mjs';
import { armChange, canvasCentre, expect, openApp, selectUpperHalf, test } from './support.mjs';

// The readout's words → the number in the committed op's transform.
const TOOLS = {
  stretch: [/^×(-?[\d.]+)$/, (t) => t.scale[0]],
  thicken: [/^×(-?[\d.]+) across$/, (t) => t.scale[1]],
  shear: [/^shear (-?[\d.]+)$/, (t) => t.shear],
  rotate: [/^(-?[\d.]+)°$/, (t) => t.rotate.degrees],
  twist: [/^(-?[\d.]+)° per unit$/, (t) => t.twist.degreesPerUnit],
};

test('the amount shows beside the pointer during a drag and is the amount committed', async ({ page }) => {
  const pageErrors = await openApp(page);
  // Part of the mesh: AnARAP cannot show a rotation of all of it (refused).
  await selectUpperHalf(page);
  const readout = page.getByTestId('drag-readout');
  const { page: [x, y] } = await canvasCentre(page);
  for (const [tool, [pattern, committedAmount]] of Object.entries(TOOLS)) {
    await page.getByTestId(`tool-${tool}`).click();
    const committed = await armChange(page, 'positions');
    await page.mouse.move(x, y);
    await page.mouse.down();
    await page.mouse.move(x + 60, y - 20, { steps: 8 });
    await expect(readout).toBeVisible();
    const text = await readout.textContent();
    expect(text).toMatch(pattern);
    // Beside the pointer: within 80 px of it.
    const box = await readout.boundingBox();
    expect(Math.hypot(box.x + box.width / 2 - (x + 60), box.y + box.height / 2 - (y - 20))).toBeLessThan(80);
    if (tool === 'stretch') await saveScreenshot(page, 'drag-readout-stretch');
    await page.mouse.up();
    await expect(readout).toHaveCount(0);
    await committed();
    const transform = await page.evaluate(() => window.anisoform.document().ops.at(-1).op.transform);
    const shown = Number(text.match(pattern)[1]);
    console.log(`${tool}: readout "${text}", committed ${committedAmount(transform)}`);
    expect(committedAmount(transform)).toBe(shown);
    expect(shown).not.toBe(0);
  }

  // Near the view's right and top edges the readout goes to the pointer's
  // other side: all of it stays in the view.
  const view = await page.getByTestId('viewport').boundingBox();
  await page.getByTestId('tool-stretch').click();
  const nearCorner = await armChange(page, 'positions');
  await page.mouse.move(x, y);
  await page.mouse.down();
  await page.mouse.move(view.x + view.width - 10, view.y + 10, { steps: 8 });
  await expect(readout).toBeVisible();
  const corner = await readout.boundingBox();
  expect(corner.x).toBeGreaterThanOrEqual(view.x);
  expect(corner.x + corner.width).toBeLessThanOrEqual(view.x + view.width);
  expect(corner.y).toBeGreaterThanOrEqual(view.y);
  expect(Math.hypot(corner.x + corner.width / 2 - (view.x + view.width - 10), corner.y + corner.height / 2 - (view.y + 10))).toBeLessThan(100);
  await page.mouse.up();
  await nearCorner();

  // Esc during a drag: the readout goes with the edit, and the panel's
  // amount is put back (it kept the dropped drag's, which Apply then used).
  const ops = await page.evaluate(() => window.anisoform.document().ops.length);
  const solved = await page.getByTestId('status-solve').textContent();
  const along = page.getByLabel('Along ×');
  await along.fill('1.2');
  await along.press('Enter');
  await page.mouse.move(x, y);
  await page.mouse.down();
  await page.mouse.move(x + 50, y, { steps: 5 });
  await expect(readout).toBeVisible();
  await expect(along).not.toHaveValue('1.2');
  await page.keyboard.press('Escape');
  await expect(readout).toHaveCount(0);
  await page.mouse.up();
  await expect(along).toHaveValue('1.2');
  // The status bar shows the last committed solve again, not the dropped drag's preview.
  await expect(page.getByTestId('status-solve')).toHaveText(solved);
  expect(await page.evaluate(() => window.anisoform.document().ops.length)).toBe(ops);
  expect(pageErrors).toEqual([]);
});
