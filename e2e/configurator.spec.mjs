// The configurator example (examples/configurator.html): the package's
// <anisoform-modeller> with no panel, three sliders bound to three edits of
// the spool, a reset and an "export GLB".
import { expect, test } from './support.mjs';

const positions = (page) => page.evaluate(() => Array.from(document.querySelector('anisoform-modeller').api.positions()));
const updates = (page) => page.getByTestId('configurator').evaluate((form) => Number(form.dataset.updates));

async function openConfigurator(page) {
  const pageErrors = [];
  page.on('pageerror', (error) => pageErrors.push(error.message));
  await page.goto('examples/configurator.html');
  await expect(page.getByTestId('configurator')).toHaveAttribute('data-state', 'idle');
  return pageErrors;
}

/** Moves a slider and lets go, as a user would ('input', then 'change'), and waits for the full solve. */
async function slide(page, name, value) {
  const before = await updates(page);
  await page.locator(`input[name=${name}]`).evaluate((slider, v) => {
    slider.value = String(v);
    slider.dispatchEvent(new Event('input', { bubbles: true }));
    slider.dispatchEvent(new Event('change', { bubbles: true }));
  }, value);
  await expect.poll(() => updates(page)).toBeGreaterThan(before);
  await expect(page.getByTestId('configurator')).toHaveAttribute('data-state', 'idle');
  await expect(page.getByTestId('configurator')).toHaveAttribute('data-solved', 'full');
}

test('each slider reshapes the spool, reset restores it exactly, export downloads a GLB', async ({ page }) => {
  const pageErrors = await openConfigurator(page);
  const base = await positions(page);
  expect(base.length).toBe(649 * 3);

  const shapes = {};
  for (const [name, value] of [['height', 1.4], ['twist', 60], ['thickness', 1.3]]) {
    await slide(page, name, value);
    shapes[name] = await positions(page);
  }
  // Each slider changed the shape from the one before it.
  expect(shapes.height).not.toEqual(base);
  expect(shapes.twist).not.toEqual(shapes.height);
  expect(shapes.thickness).not.toEqual(shapes.twist);
  // Height stretches along the axis (x): the spool gets longer.
  const extentX = (p) => { let lo = Infinity; let hi = -Infinity; for (let i = 0; i < p.length; i += 3) { lo = Math.min(lo, p[i]); hi = Math.max(hi, p[i]); } return hi - lo; };
  expect(extentX(shapes.height) / extentX(base)).toBeGreaterThan(1.1);

  // Back to a slider's earlier value: the same shape as then (solved again from the base).
  await slide(page, 'thickness', 1);
  expect(await positions(page)).toEqual(shapes.twist);

  const before = await updates(page);
  await page.getByTestId('reset').click();
  await expect.poll(() => updates(page)).toBeGreaterThan(before);
  await expect(page.getByTestId('configurator')).toHaveAttribute('data-state', 'idle');
  expect(await positions(page)).toEqual(base);
  await expect(page.locator('input[name=height]')).toHaveValue('1');

  await slide(page, 'twist', -45);
  const downloading = page.waitForEvent('download');
  await page.getByTestId('export-glb').click();
  const download = await downloading;
  expect(download.suggestedFilename()).toBe('spool.glb');
  const { readFile } = await import('node:fs/promises');
  const bytes = await readFile(await download.path());
  expect(bytes.subarray(0, 4).toString('latin1')).toBe('glTF');
  expect(pageErrors).toEqual([]);
});

test('dragging a slider updates the shape live (update rate)', async ({ page }) => {
  const pageErrors = await openConfigurator(page);
  // A 2 s drag of the height slider: a new value every animation frame
  // ('input' only: previews), then the release ('change': the full solve).
  const result = await page.evaluate(async () => {
    const form = document.querySelector('[data-testid=configurator]');
    const slider = form.elements.height;
    const { api } = document.querySelector('anisoform-modeller');
    let changedFrames = 0;
    let last = api.positions();
    const start = Number(form.dataset.updates);
    const t0 = performance.now();
    while (performance.now() - t0 < 2000) {
      const phase = (performance.now() - t0) / 2000;
      slider.value = String(1 + 0.6 * Math.sin(phase * Math.PI * 2));
      slider.dispatchEvent(new Event('input', { bubbles: true }));
      await new Promise(requestAnimationFrame);
      const now = api.positions();
      if (now.some((v, i) => v !== last[i])) changedFrames++;
      last = now;
    }
    const seconds = (performance.now() - t0) / 1000;
    const updates = Number(form.dataset.updates) - start;
    slider.dispatchEvent(new Event('change', { bubbles: true }));
    return { seconds, updates, changedFrames };
  });
  await expect(page.getByTestId('configurator')).toHaveAttribute('data-solved', 'full');
  await expect(page.getByTestId('configurator')).toHaveAttribute('data-state', 'idle');
  // A solve is one slider state solved again from the base (undo, then the
  // edits); frames with new positions also count the base shown in between.
  const rate = result.updates / result.seconds;
  test.info().annotations.push({ type: 'configurator slider solves per second (649 vertices)', description: rate.toFixed(1) });
  console.log(`configurator: ${result.updates} slider solves (${rate.toFixed(1)}/s), ${result.changedFrames} frames with changed positions in ${result.seconds.toFixed(2)} s`);
  expect(rate).toBeGreaterThan(5);
  expect(pageErrors).toEqual([]);
});
