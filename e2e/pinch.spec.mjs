// A second finger turns a stroke into a camera gesture: with Select, Stretch
// or Arrows, a touch that starts on the mesh begins the tool's stroke; when a
// second finger lands, the stroke is dropped (no paint kept, no deform, no
// arrow, no undo step) and the two fingers pinch-zoom the camera. The same
// stroke with one finger does edit: the touch path itself works.
import { saveScreenshot } from './artifacts.mjs';
import { swipe, touchScreen } from './touch.mjs';
import { canvasCentre, evaluateBulk, expect, openApp, test } from './support.mjs';

test.use({ viewport: { width: 390, height: 844 }, hasTouch: true, isMobile: true });

const state = (page) => evaluateBulk(page, () => ({
  selection: Array.from(window.anisoform.selection()),
  positions: Array.from(window.anisoform.positions()),
  ops: window.anisoform.document().ops.length,
}));

const cameraDistance = (page) => page.evaluate(() => {
  const { position, target } = window.anisoform.camera();
  return Math.hypot(...position.map((value, axis) => value - target[axis]));
});

/** Counts the committed changes (any reason) from now on. */
const countChanges = (page) => page.evaluate(() => {
  window.__changes = [];
  window.anisoform.on('change', ({ reason }) => window.__changes.push(reason));
});
const changes = (page) => page.evaluate(() => window.__changes);

/** One finger strokes on the mesh, a second lands and both spread apart. */
async function strokeThenPinch(screen, [x, y]) {
  await screen.start([[x, y]]);
  for (let step = 1; step <= 5; step++) await screen.move([[x + 6 * step, y]]);
  const first = [x + 30, y];
  await screen.start([first, [x + 30, y + 40]]);
  for (let step = 1; step <= 8; step++) {
    await screen.move([[first[0], first[1] - 12 * step], [x + 30, y + 40 + 12 * step]]);
  }
  await screen.end();
}

for (const [tool, committed] of [['select', 'selection'], ['stretch', 'positions'], ['arrows', null]]) {
  test(`a second finger cancels the ${tool} stroke and pinch-zooms instead`, async ({ page }) => {
    const pageErrors = await openApp(page);
    await page.getByTestId(`tool-${tool}`).tap();
    const screen = await touchScreen(page);
    const { page: centre } = await canvasCentre(page);
    const arrowsPlaced = page.getByText(/arrow\(s\) placed/);

    // One finger: the tool edits (a committed change, or an arrow placed).
    await countChanges(page);
    await swipe(screen, centre, [48, 0]);
    if (committed) {
      await expect.poll(() => changes(page)).toContain(committed);
      await page.evaluate(() => window.anisoform.undo());
    } else {
      await expect(arrowsPlaced).toHaveText('1 arrow(s) placed');
      // About one tap in three right after the swipe did not reach the button
      // (the count had not changed 3 s later; the test then failed at its end
      // on the arrow it had not cleared). Clearing is idempotent: tap until
      // the count says so, so the check below is about the pinch only.
      await expect(async () => {
        await page.getByRole('button', { name: 'Clear arrows' }).tap();
        await expect(arrowsPlaced).toHaveText('0 arrow(s) placed', { timeout: 1000 });
      }).toPass({ timeout: 10_000 });
    }

    const before = await state(page);
    const distanceBefore = await cameraDistance(page);
    await countChanges(page);
    await strokeThenPinch(screen, centre);
    await saveScreenshot(page, `pinch-${tool}`);
    // Give a cancelled solve time to (wrongly) arrive.
    await page.waitForTimeout(1000);

    expect(await changes(page)).toEqual([]);
    expect(await state(page)).toEqual(before);
    if (!committed) await expect(arrowsPlaced).toHaveText('0 arrow(s) placed');
    expect(await cameraDistance(page)).toBeLessThan(distanceBefore * 0.9);
    expect(pageErrors).toEqual([]);
  });
}
