// The configurator example (examples/configurator.html): the package's
// <anisoform-modeller> with no panel, three sliders bound to the three ops
// of its edit document through api.setParameter, a reset and an "export GLB".
import { expect, test } from './support.mjs';

const modeller = (page, read) => page.evaluate(`(${read})(document.querySelector('anisoform-modeller').api)`);
const positions = (page) => modeller(page, (api) => Array.from(api.positions()));
const ops = (page) => modeller(page, (api) => api.document().ops);
const bitwise = (a, b) => a.length === b.length && a.every((value, i) => Object.is(value, b[i]));

async function openConfigurator(page) {
  const pageErrors = [];
  page.on('pageerror', (error) => pageErrors.push(error.message));
  await page.goto('examples/configurator.html');
  await expect(page.getByTestId('configurator')).toHaveAttribute('data-state', 'idle');
  return pageErrors;
}

/** Moves a slider and lets go, as a user would ('input', then 'change'), and waits for the commit. */
async function slide(page, name, value) {
  await page.locator(`input[name=${name}]`).evaluate((slider, v) => {
    slider.value = String(v);
    slider.dispatchEvent(new Event('input', { bubbles: true }));
    slider.dispatchEvent(new Event('change', { bubbles: true }));
  }, value);
  await expect(page.getByTestId('configurator')).toHaveAttribute('data-state', 'idle');
  await expect(page.getByTestId('configurator')).toHaveAttribute('data-solved', 'full');
}

// The amounts the document's three ops hold: [height, twist degrees per unit, thickness].
// (A neutral stretch is stored without its scale: [1, 1] is the default.)
const amounts = (list) => [list[0].op.transform.scale ?? [1, 1], list[1].op.transform.twist.degreesPerUnit,
  list[2].op.transform.scale ?? [1, 1]];

test('each slider sets its op by setParameter, reset restores the shape exactly, export downloads a GLB', async ({ page }) => {
  const pageErrors = await openConfigurator(page);
  const base = await positions(page);
  expect(base.length).toBe(649 * 3);
  const initialOps = await ops(page);
  expect(initialOps.map((op) => op.op.method)).toEqual(['anarap', 'anarap', 'anarap']);
  expect(amounts(initialOps)).toEqual([[1, 1], 0, [1, 1]]);
  const length = await modeller(page, (api) => { const p = api.positions(); let lo = Infinity; let hi = -Infinity; for (let i = 0; i < p.length; i += 3) { lo = Math.min(lo, p[i]); hi = Math.max(hi, p[i]); } return hi - lo; });

  const shapes = {};
  for (const [name, value] of [['height', 1.4], ['twist', 60], ['thickness', 1.3]]) {
    await slide(page, name, value);
    shapes[name] = await positions(page);
  }
  // The same three ops, now with the sliders' amounts (never new ops).
  const edited = await ops(page);
  expect(edited.map((op) => op.id)).toEqual(initialOps.map((op) => op.id));
  const [height, twist, thickness] = amounts(edited);
  expect(height).toEqual([1.4, 1]);
  expect(twist).toBeCloseTo(60 / length, 6);
  expect(thickness).toEqual([1, 1.3]);
  // Each slider changed the shape from the one before it.
  expect(shapes.height).not.toEqual(base);
  expect(shapes.twist).not.toEqual(shapes.height);
  expect(shapes.thickness).not.toEqual(shapes.twist);
  // Height stretches along the axis (x): the spool gets longer.
  const extentX = (p) => { let lo = Infinity; let hi = -Infinity; for (let i = 0; i < p.length; i += 3) { lo = Math.min(lo, p[i]); hi = Math.max(hi, p[i]); } return hi - lo; };
  expect(extentX(shapes.height) / extentX(base)).toBeGreaterThan(1.1);

  // The committed shape is the document's replay, bitwise.
  const replayed = await modeller(page, async (api) => { await api.open(api.document()); return Array.from(api.positions()); });
  expect(bitwise(replayed, shapes.thickness)).toBe(true);

  // Back to a slider's earlier value: the same document as then, so the same shape.
  await slide(page, 'thickness', 1);
  expect(bitwise(await positions(page), shapes.twist)).toBe(true);

  await page.getByTestId('reset').click();
  await expect(page.getByTestId('configurator')).toHaveAttribute('data-state', 'idle');
  await expect.poll(async () => amounts(await ops(page))).toEqual([[1, 1], 0, [1, 1]]);
  expect(bitwise(await positions(page), base)).toBe(true);
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

test('undo and redo in the view take the slider changes back and forth, and the sliders follow', async ({ page }) => {
  const pageErrors = await openConfigurator(page);
  const base = await positions(page);
  await slide(page, 'height', 1.4);
  const higher = await positions(page);
  await slide(page, 'twist', 60);
  const twisted = await positions(page);
  const height = page.locator('input[name=height]');
  const twist = page.locator('input[name=twist]');
  // Keys reach the modeller when the focus is in it (the view).
  await page.locator('anisoform-modeller canvas').focus();
  const press = async (keys, expected) => {
    const changed = page.evaluate(() => new Promise((resolve) => {
      document.querySelector('anisoform-modeller').addEventListener('change', (event) => {
        if (event.detail.reason === 'document') resolve();
      });
    }));
    await page.keyboard.press(keys);
    await changed;
    expect(bitwise(await positions(page), expected)).toBe(true);
  };
  await press('Control+z', higher);
  await expect(twist).toHaveValue('0');
  await expect(height).toHaveValue('1.4');
  await press('Control+z', base);
  await expect(height).toHaveValue('1');
  await press('Control+Shift+z', higher);
  await expect(height).toHaveValue('1.4');
  await press('Control+Shift+z', twisted);
  await expect(twist).toHaveValue('60');
  await expect(page.locator('output[for=twist]')).toHaveText('60°');
  // Further back than the slider changes: the first edits go, their sliders wait.
  await press('Control+z', higher);
  await press('Control+z', base);
  await page.keyboard.press('Control+z');
  await expect(page.locator('input[name=thickness]')).toBeDisabled();
  expect(pageErrors).toEqual([]);
});

// A 2 s drag of a slider: a new value every animation frame ('input' only:
// previews), then the release ('change': the commit). The document must not
// change while dragging, and after the release hold the final value in the
// same op.
async function drag(page, name, amplitude) {
  return page.evaluate(async ({ name, amplitude }) => {
    const form = document.querySelector('[data-testid=configurator]');
    const slider = form.elements[name];
    const { api } = document.querySelector('anisoform-modeller');
    const before = JSON.stringify(api.document());
    let previews = 0;
    let changedFrames = 0;
    let seen = 0;
    const off = api.on('positions', ({ live }) => { if (live) previews++; });
    const t0 = performance.now();
    while (performance.now() - t0 < 2000) {
      slider.value = String(1 + amplitude * Math.sin(((performance.now() - t0) / 2000) * Math.PI * 2));
      slider.dispatchEvent(new Event('input', { bubbles: true }));
      await new Promise(requestAnimationFrame);
      if (previews > seen) changedFrames++;
      seen = previews;
    }
    const seconds = (performance.now() - t0) / 1000;
    off();
    const unchanged = JSON.stringify(api.document()) === before;
    slider.dispatchEvent(new Event('change', { bubbles: true }));
    return { seconds, previews, changedFrames, unchanged, value: Number(slider.value) };
  }, { name, amplitude });
}

test('dragging a slider previews live through setParameter and commits the release in its op', { tag: '@speed' }, async ({ page }) => {
  const pageErrors = await openConfigurator(page);
  const initialOps = await ops(page);
  // height is the first op (a preview replays the three ops), thickness the
  // last (a preview is a warm-started solver iteration).
  for (const [name, amplitude, index] of [['height', 0.6, 0], ['thickness', 0.4, 2]]) {
    const result = await drag(page, name, amplitude);
    await expect(page.getByTestId('configurator')).toHaveAttribute('data-state', 'idle');
    await expect(page.getByTestId('configurator')).toHaveAttribute('data-solved', 'full');
    expect(result.unchanged).toBe(true);
    const after = await ops(page);
    expect(after.map((op) => op.id)).toEqual(initialOps.map((op) => op.id));
    const scale = after[index].op.transform.scale;
    expect(scale[index === 0 ? 0 : 1]).toBeCloseTo(result.value, 12);
    const rate = result.changedFrames / result.seconds;
    test.info().annotations.push({ type: `configurator ${name} previews per second (649 vertices)`, description: rate.toFixed(1) });
    console.log(`configurator ${name}: ${result.previews} previews, ${result.changedFrames} frames with new positions `
      + `in ${result.seconds.toFixed(2)} s (${rate.toFixed(1)}/s)`);
    // Several distinct previews arrive during the drag; the rate is printed,
    // not asserted (speed belongs to the benchmarks; the shared cores swing it).
    expect(result.changedFrames).toBeGreaterThanOrEqual(3);
  }
  expect(pageErrors).toEqual([]);
});
