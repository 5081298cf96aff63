// Apply in the tool panel never fails silently: when an edit cannot run (no
// screen drag yet for the 'Screen drag' direction, no arrows for 'Arrows',
// 'ARAP with handles', which has no amount), the error banner and the API's
// 'error' event say why and what to do, and the mesh and history stay. An
// edit no direction changes (a twist, a rotation about the normal) needs none.
import { armChange, evaluateBulk, expect, meshPath, openApp, selectUpperHalf, startLongCommit, test, uploadFile } from './support.mjs';

async function recordErrors(page) {
  await page.evaluate(() => {
    window.__errors = [];
    window.anisoform.on('error', (event) => window.__errors.push(event));
  });
}

async function applyStretch(page, along) {
  await page.getByTestId('tool-stretch').click();
  const field = page.getByLabel('Along ×');
  await field.click();
  await field.fill(String(along));
  await field.press('Tab');
  await page.getByTestId('apply-stretch').click();
}

async function expectRefusal(page, { before, words }) {
  const banner = page.getByTestId('error');
  await expect(banner).toBeVisible();
  for (const word of words) await expect(banner).toContainText(word);
  const errors = await page.evaluate(() => window.__errors);
  expect(errors).toHaveLength(1);
  expect(errors[0].code).toBe('bad-parameter');
  for (const word of words) expect(errors[0].message).toContain(word);
  expect(await evaluateBulk(page, () => Array.from(window.anisoform.positions()))).toEqual(before);
  expect(await page.evaluate(() => window.anisoform.undo())).toBe(false);
}

test('Apply on a fresh page (screen direction, no drag yet) says to drag first', async ({ page }) => {
  const pageErrors = await openApp(page);
  await recordErrors(page);
  const before = await evaluateBulk(page, () => Array.from(window.anisoform.positions()));
  await applyStretch(page, 2);
  await expectRefusal(page, { before, words: ['Stretch was not applied', 'drag on the mesh', 'direction source'] });
  expect(pageErrors).toEqual([]);
});

test('Apply of a twist or a rotation about the normal needs no drag first; about u it does', async ({ page }) => {
  const pageErrors = await openApp(page);
  await recordErrors(page);
  await selectUpperHalf(page);
  const positions = () => evaluateBulk(page, () => Array.from(window.anisoform.positions()));
  const opCount = () => page.evaluate(() => window.anisoform.document().ops.length);
  const rest = await positions();
  await page.getByTestId('tool-twist').click();
  let committed = await armChange(page, 'positions');
  await page.getByTestId('apply-twist').click();
  await committed();
  expect(await opCount()).toBe(1);
  const twisted = await positions();
  expect(twisted).not.toEqual(rest);

  await page.getByTestId('tool-rotate').click();
  await page.locator('#rotate-axis').selectOption('n');
  committed = await armChange(page, 'positions');
  await page.getByTestId('apply-rotate').click();
  await committed();
  expect(await opCount()).toBe(2);
  expect(await positions()).not.toEqual(twisted);
  expect(await page.evaluate(() => window.__errors)).toEqual([]);
  await expect(page.getByTestId('error')).toBeHidden();

  // About the direction (u), the rotation does depend on it: refused as a stretch is.
  const before = await positions();
  await page.locator('#rotate-axis').selectOption('u');
  await page.getByTestId('apply-rotate').click();
  await expect(page.getByTestId('error')).toContainText('Rotate was not applied');
  await expect(page.getByTestId('error')).toContainText('drag on the mesh');
  expect(await positions()).toEqual(before);
  expect(await opCount()).toBe(2);
  expect(pageErrors).toEqual([]);
});

test('Apply with the Arrows source and no arrows says to place arrows', async ({ page }) => {
  const pageErrors = await openApp(page);
  await recordErrors(page);
  const before = await evaluateBulk(page, () => Array.from(window.anisoform.positions()));
  await page.locator('#direction-source').selectOption('arrows');
  await applyStretch(page, 2);
  await expectRefusal(page, { before, words: ['Stretch was not applied', 'Arrows tool'] });
  expect(pageErrors).toEqual([]);
});

test('Apply with ARAP with handles says to drag the selection instead', async ({ page }) => {
  const pageErrors = await openApp(page);
  await recordErrors(page);
  const before = await evaluateBulk(page, () => Array.from(window.anisoform.positions()));
  await page.locator('#direction-source').selectOption('global');
  await page.locator('#solver-method').selectOption('arap');
  await applyStretch(page, 2);
  await expectRefusal(page, { before, words: ['Stretch was not applied', 'ARAP with handles', 'drag the selection'] });
  expect(pageErrors).toEqual([]);
});

test('a refused API edit reaches the banner and the error event once', async ({ page }) => {
  await openApp(page);
  await recordErrors(page);
  const rejection = await page.evaluate(() =>
    window.anisoform.deform({ method: 'anarap', direction: { type: 'sideways' }, transform: { scale: [2, 1] } })
      .then(() => null, (error) => ({ code: error.code, message: error.message })));
  expect(rejection.code).toBe('bad-parameter');
  const errors = await page.evaluate(() => window.__errors);
  expect(errors).toEqual([rejection]);
  await expect(page.getByTestId('error')).toContainText('direction.type must be one of');
  // Not an op at all: said as such, not as fields '0', '1', … of a string.
  const notAnOp = await page.evaluate(() => window.anisoform.deform('stretch').then(() => null, (error) => error.message));
  expect(notAnOp).toBe('The edit failed: op must be an object');
});

test('an edit the solver refuses is reported once', async ({ page }) => {
  await openApp(page);
  await recordErrors(page);
  // The core refuses a constraint at a vertex the mesh does not have.
  const rejection = await page.evaluate(() =>
    window.anisoform.deform({
      method: 'anarap',
      direction: { type: 'constraints', constraints: [{ vertex: 10_000_000, direction: [1, 0, 0] }] },
      transform: { scale: [2, 1] },
    }).then(() => null, (error) => error.message));
  expect(rejection).toContain('failed');
  await expect(page.getByTestId('error')).toBeVisible();
  expect(await page.evaluate(() => window.__errors.map((event) => event.message))).toEqual([rejection]);
  // In the call's words: the edit it made, not the document's place for it ("document.ops[0] (id 'op-1')").
  const pinned = await page.evaluate(() =>
    window.anisoform.deform({ method: 'arap', pins: [999_999], move: [0, 0.1, 0] }).then(() => null, (error) => error.message));
  expect(pinned).toBe('Move (ARAP) failed: pinned vertex 999999 is out of range (the mesh has 2930 vertices)');
});

test('Apply is off while its edit solves: clicks and Enter meanwhile stack no second edit, and the focus stays on it', async ({ page }) => {
  const pageErrors = await openApp(page);
  // A 26k-vertex mesh, so that the commit lasts long enough to click into.
  expect((await uploadFile(page, meshPath('closed/armadillo.off'))).ok).toBe(true);
  await page.evaluate(() => window.anisoform.select({ all: true }));
  await page.getByTestId('tool-stretch').click();
  await page.locator('#direction-source').selectOption('global');
  const apply = page.getByTestId('apply-stretch');
  const focused = () => page.evaluate(() => document.activeElement?.dataset.testid ?? document.activeElement?.tagName);
  await apply.focus();
  await page.keyboard.press('Enter');
  await expect(apply).toBeDisabled();
  expect(await focused()).toBe('apply-stretch');
  await apply.click({ force: true });
  await page.keyboard.press('Enter');
  await expect(apply).toBeEnabled({ timeout: 60_000 });
  expect(await page.evaluate(() => window.anisoform.document().ops.length)).toBe(1);
  // Still on Apply: Enter applies again.
  expect(await focused()).toBe('apply-stretch');
  await page.keyboard.press('Enter');
  await expect.poll(() => page.evaluate(() => window.anisoform.document().ops.length), { timeout: 60_000 }).toBe(2);
  expect(pageErrors).toEqual([]);
});

test('while a commit solves, a press on the mesh with the brush or a tool turns the view and says why it does not paint or edit', async ({ page }) => {
  const pageErrors = await openApp(page);
  await startLongCommit(page);
  await expect(page.getByTestId('cancel-solve')).toBeVisible();
  const before = await evaluateBulk(page, () => ({ selection: Array.from(window.anisoform.selection()), camera: JSON.stringify(window.anisoform.camera()) }));
  const notice = page.getByTestId('notice');
  const view = await page.getByTestId('viewport').boundingBox();
  const pressOnMesh = async () => {
    await page.mouse.move(view.x + view.width / 2, view.y + view.height / 2);
    await page.mouse.down();
    await page.mouse.move(view.x + view.width / 2 + 40, view.y + view.height / 2, { steps: 4 });
    await page.mouse.up();
  };
  await page.getByTestId('tool-select').click();
  await pressOnMesh();
  await expect(notice).toContainText('Painting the selection waits until the solve has ended: press Esc to cancel it.');
  await page.getByTestId('tool-stretch').click();
  await pressOnMesh();
  await expect(notice).toContainText('Dragging an edit waits until the solve has ended');
  const after = await evaluateBulk(page, () => ({ selection: Array.from(window.anisoform.selection()), camera: JSON.stringify(window.anisoform.camera()) }));
  // Nothing painted; the view turned instead.
  expect(after.selection).toEqual(before.selection);
  expect(after.camera).not.toBe(before.camera);
  await page.keyboard.press('Escape');
  expect(await page.evaluate(() => window.__long)).toBe('cancelled');
  // The cancel's notice replaces the wait's.
  await expect(notice).toContainText('Cancelled: the solve was stopped');
  expect(pageErrors).toEqual([]);
});

test('Undo and Redo keep the focus at either end of the history', async ({ page }) => {
  const pageErrors = await openApp(page);
  await page.evaluate(async () => {
    await window.anisoform.select({ all: true });
    await window.anisoform.deform({ method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: [1.2, 1] } });
  });
  const undo = page.getByTestId('undo');
  const redo = page.getByTestId('redo');
  // Two steps: the selection and the edit.
  await undo.focus();
  await page.keyboard.press('Enter');
  await expect.poll(() => page.evaluate(() => window.anisoform.document().ops.length)).toBe(0);
  await page.keyboard.press('Enter');
  await expect(undo).toBeDisabled();
  await expect(undo).toBeFocused();
  await page.keyboard.press('Enter'); // nothing left to undo: nothing happens
  await page.keyboard.press('Tab');
  await expect(redo).toBeFocused();
  await page.keyboard.press('Enter');
  await page.keyboard.press('Enter');
  await expect(redo).toBeDisabled();
  await expect(redo).toBeFocused();
  expect(await page.evaluate(() => window.anisoform.document().ops.length)).toBe(1);
  expect(pageErrors).toEqual([]);
});

test('Apply with an amount the core refuses says so in the panel\'s words', async ({ page }) => {
  const pageErrors = await openApp(page);
  await recordErrors(page);
  const before = await evaluateBulk(page, () => Array.from(window.anisoform.positions()));
  await page.locator('#direction-source').selectOption('global');
  await applyStretch(page, 0);
  await expectRefusal(page, { before, words: ['Stretch', 'stretch along (su) must be positive, got 0'] });
  expect((await page.evaluate(() => window.__errors))[0].message).not.toContain('op.transform');
  expect(pageErrors).toEqual([]);
});

test('a value a field does not take is said, not only put back', async ({ page }) => {
  const pageErrors = await openApp(page);
  await page.getByTestId('tool-stretch').click();
  const along = page.getByLabel('Along ×');
  const kept = await along.inputValue();
  await along.fill('abc');
  await along.press('Tab');
  await expect(along).toHaveValue(kept);
  const notice = page.getByTestId('notice');
  await expect(notice).toContainText(`Along ×: 'abc' is not a number; ${kept} is kept`);
  // A brush radius beyond its bounds is used at the bound, and said.
  await page.getByTestId('tool-select').click();
  const radius = page.locator('#brush-radiusPercent');
  await radius.fill('500');
  await radius.press('Tab');
  await expect(radius).toHaveValue('100');
  await expect(notice).toContainText('Radius %: 500 is out of range (0.5 to 100); 100 is used');
  expect(pageErrors).toEqual([]);
});

// The iteration cap is a whole number: "2.5" (or "2,5") was kept without a
// word, and every later edit failed "op.maxIterations must be an integer".
test('the Iterations field refuses a fraction, says so and keeps its value; the next edit runs', async ({ page }) => {
  const pageErrors = await openApp(page);
  const iterations = page.locator('#solver-iterations');
  await expect(iterations).toHaveValue('50');
  const notice = page.getByTestId('notice');
  for (const typed of ['2.5', '2,5']) {
    await iterations.fill(typed);
    await iterations.press('Tab');
    await expect(iterations).toHaveValue('50');
    await expect(notice).toHaveText(new RegExp(`Iterations: '${typed}' is not a whole number; 50 is kept`));
  }
  await page.getByTestId('tool-thicken').click();
  await page.locator('#direction-source').selectOption('global');
  await page.getByTestId('apply-thicken').click();
  await expect.poll(() => page.evaluate(() => window.anisoform.document().ops.length)).toBe(1);
  expect(await page.evaluate(() => window.anisoform.document().ops[0].op.maxIterations)).toBe(50);
  await expect(page.getByTestId('error')).toBeHidden();
  expect(pageErrors).toEqual([]);
});

// "Radius %: '1,000.5' is not a number; 1 is kept" stood after the user typed
// a value the field took; another field's value leaves it.
test('a field\'s refused-value notice goes when that field takes a value, not when another does', async ({ page }) => {
  const pageErrors = await openApp(page);
  const radius = page.locator('#brush-radiusPercent');
  const softness = page.locator('#brush-softnessPercent');
  const notice = page.getByTestId('notice');
  await radius.fill('1,000.5');
  await radius.press('Tab');
  await expect(notice).toContainText("Radius %: '1,000.5' is not a number; 8 is kept");
  await softness.fill('40');
  await softness.press('Tab');
  await expect(notice).toBeVisible();
  await radius.fill('12');
  await radius.press('Tab');
  await expect(radius).toHaveValue('12');
  await expect(notice).toBeHidden();
  expect(pageErrors).toEqual([]);
});
