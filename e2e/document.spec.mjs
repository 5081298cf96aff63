// The edit document (issue 8 items 1-4): every committed edit is a resolved
// op; replaying the document on a fresh page gives bitwise the same
// positions; ops can be toggled and re-parameterised (later ops re-run);
// autosave restores the work after a reload; a slider on the last op updates
// live; a bad document is refused with its code and the work kept.
import { readFileSync } from 'node:fs';

import { schemaErrors } from '../docs/document-schema.mjs';
import { armChange, evaluateBulk, expect, meshPath, openApp, recordWorkerRequests, test, uploadFile } from './support.mjs';

// Three edits on Spot: a soft region stretch, a twist of a box, a shear of
// a selection built with 'add'.
async function editSpot(page) {
  return evaluateBulk(page, async () => {
    const api = window.anisoform;
    await api.select({ sphere: { center: [0, 0.3, 0.5], radius: 0.4 } }, { falloff: 0.2 });
    await api.deform({ method: 'anarap', direction: { type: 'global', vector: [0, 0, 1] }, transform: { scale: [1.4, 1] } });
    const afterOne = Array.from(api.positions());
    await api.select({ box: { min: [-1, -1, -1], max: [1, 0, 1] } });
    await api.deform({ method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] },
      transform: { twist: { axis: [0, 1, 0], degreesPerUnit: 30 } } });
    const afterTwo = Array.from(api.positions());
    await api.select({ sphere: { center: [0.3, 0, 0], radius: 0.3 } });
    await api.select({ sphere: { center: [-0.3, 0, 0], radius: 0.3 } }, { mode: 'add' });
    await api.deform({ method: 'andefgrad', direction: { type: 'global', vector: [1, 0, 0] }, transform: { shear: 0.3 } });
    return { afterOne, afterTwo, afterThree: Array.from(api.positions()), document: api.document() };
  });
}

// The record under `prefix` + the id of the tab that saved last (autosave.js), or null.
const savedRecord = (page, prefix) => page.evaluate((keyPrefix) => new Promise((resolve) => {
  const request = indexedDB.open('anisoform', 1);
  request.onsuccess = () => {
    const store = request.result.transaction('autosave').objectStore('autosave');
    const latest = store.get('current');
    latest.onsuccess = () => {
      if (!latest.result) return resolve(null);
      const get = store.get(`${keyPrefix}${latest.result.tab}`);
      // Without the mesh file (a Blob, which does not cross to the test).
      get.onsuccess = () => resolve(get.result ? { ...get.result, meshBytes: undefined } : null);
    };
  };
}), prefix);

// The view saved beside that work (view-autosave.js), or null.
const savedView = (page) => savedRecord(page, 'view:');

const bitwise = (a, b) => a.length === b.length && a.every((value, i) => Object.is(value, b[i]));

// The autosaved work a new tab would restore, {meshName, document}.
const savedWork = (page) => savedRecord(page, '').then((record) => record && { meshName: record.meshName, document: record.document });

test('a document replays on a fresh page to bitwise the same positions', async ({ page, browser }) => {
  const pageErrors = await openApp(page);
  const { afterThree, document } = await editSpot(page);
  expect(document.format).toBe('anisoform-document');
  expect(document.ops.map((op) => op.op.direction.type)).toEqual(['global', 'global', 'global']);
  expect(document.ops[1].op.transform.twist.origin).toBeUndefined(); // the region's, worked out by replay
  expect(document.regions[0].steps[0].region.sphere.radius).toBe(0.4);
  expect(document.regions.at(-1).steps.map((step) => step.mode ?? 'replace')).toEqual(['replace', 'add']);
  expect(schemaErrors(document)).toEqual([]);

  const fresh = await browser.newPage();
  const freshErrors = await openApp(fresh);
  const replayed = await evaluateBulk(fresh, async (json) => {
    await window.anisoform.open(json);
    return { positions: Array.from(window.anisoform.positions()), document: window.anisoform.document() };
  }, document);
  expect(bitwise(replayed.positions, afterThree)).toBe(true);
  expect(replayed.document.ops.map((op) => op.id)).toEqual(document.ops.map((op) => op.id));
  await fresh.close();
  expect(pageErrors).toEqual([]);
  expect(freshErrors).toEqual([]);
});

test('an op toggled off is skipped and its amounts re-run the later ops', async ({ page }) => {
  const pageErrors = await openApp(page);
  const { afterOne, afterTwo, afterThree, document } = await editSpot(page);
  const [, second, third] = document.ops;
  await expect(page.getByTestId('op-list').locator('li')).toHaveCount(3);

  // The last op off: the state after two ops, bitwise.
  // The 'document' change comes after the re-run.
  let rerun = await armChange(page, 'document');
  await page.getByTestId(`op-toggle-${third.id}`).uncheck();
  await rerun();
  expect(await page.evaluate(() => window.anisoform.document().ops[2].enabled)).toBe(false);
  expect(bitwise(await evaluateBulk(page, () => Array.from(window.anisoform.positions())), afterTwo)).toBe(true);
  rerun = await armChange(page, 'document');
  await page.getByTestId(`op-toggle-${third.id}`).check();
  await rerun();
  expect(await page.evaluate(() => window.anisoform.document().ops[2].enabled)).toBe(true);
  expect(bitwise(await evaluateBulk(page, () => Array.from(window.anisoform.positions())), afterThree)).toBe(true);

  // The middle op's twist amount from the panel: the op and the one after re-run.
  await page.getByTestId(`op-select-${second.id}`).click();
  const amount = page.getByTestId(`op-amount-${second.id}-Twist (degrees/unit)`);
  await expect(amount).toHaveValue('30');
  rerun = await armChange(page, 'document');
  await amount.fill('10');
  await amount.dispatchEvent('change');
  await rerun();
  expect(await page.evaluate(() => window.anisoform.document().ops[1].op.transform.twist.degreesPerUnit)).toBe(10);
  const retwisted = await evaluateBulk(page, () => Array.from(window.anisoform.positions()));
  expect(bitwise(retwisted, afterThree)).toBe(false);
  // Back to 30 by the API: bitwise the original three-op result.
  const restored = await evaluateBulk(page, async (id) => {
    await window.anisoform.setParameter(id, { transform: { twist: { ...window.anisoform.document().ops[1].op.transform.twist, degreesPerUnit: 30 } } });
    return Array.from(window.anisoform.positions());
  }, second.id);
  expect(bitwise(restored, afterThree)).toBe(true);

  // Each change of an op is a step of the history, as each commit is: undo
  // and redo re-run the op with its value before or after (here the undo
  // steps named in the Undo button, back over every change to the shear's commit).
  const positions = () => evaluateBulk(page, () => Array.from(window.anisoform.positions()));
  const ops = () => page.evaluate(() => window.anisoform.document().ops.map((op) => `${op.enabled}:${JSON.stringify(op.op.transform)}`));
  const undoTitle = () => page.getByTestId('undo').getAttribute('title');
  const step = async (which, solves = true) => {
    const done = solves ? await armChange(page, 'document') : null;
    expect(await page.evaluate((name) => window.anisoform[name](), which)).toBe(true);
    if (done) await done();
  };
  expect(await undoTitle()).toBe('Undo Change the amounts of Twist (AnARAP) (Ctrl+Z)');
  await step('undo');
  expect(bitwise(await positions(), retwisted)).toBe(true);
  await step('undo');
  expect(bitwise(await positions(), afterThree)).toBe(true);
  // (Opening the second op in the panel showed its region: no step.)
  expect(await undoTitle()).toBe('Undo Turn on Shear (AnDefGrad) (Ctrl+Z)');
  await step('undo');
  expect((await ops())[2]).toMatch(/^false:/);
  expect(bitwise(await positions(), afterTwo)).toBe(true);
  await step('undo');
  expect((await ops())[2]).toMatch(/^true:/);
  expect(await undoTitle()).toBe('Undo Shear (AnDefGrad) (Ctrl+Z)');
  const beforeShearUndo = await ops();
  await step('undo'); // the shear's commit
  expect(await page.evaluate(() => window.anisoform.document().ops.length)).toBe(2);
  expect(bitwise(await positions(), afterTwo)).toBe(true);
  // Redo goes forward over the same steps.
  await step('redo');
  expect(await ops()).toEqual(beforeShearUndo);
  await step('redo');
  expect((await ops())[2]).toMatch(/^false:/);
  expect(bitwise(await positions(), afterTwo)).toBe(true);
  await step('redo');
  await step('redo');
  expect(await page.evaluate(() => window.anisoform.document().ops[1].op.transform.twist.degreesPerUnit)).toBe(10);
  expect(bitwise(await positions(), retwisted)).toBe(true);
  expect(await page.getByTestId('redo').getAttribute('title')).toBe('Redo Change the amounts of Twist (AnARAP) (Ctrl+Shift+Z)');

  // A refused amount (a stretch by -1), or a field left empty, leaves the op,
  // its field and the history as they were.
  const first = document.ops[0];
  await page.getByTestId(`op-select-${first.id}`).click();
  const along = page.getByTestId(`op-amount-${first.id}-Stretch along`);
  await expect(along).toHaveValue('1.4');
  const refused = page.evaluate(() => new Promise((resolve) => {
    const off = window.anisoform.on('error', ({ message }) => { off(); resolve(message); });
  }));
  await along.fill('-1');
  await along.dispatchEvent('change');
  // In the list's words: the op's label and the field's name, not the document's places.
  expect(await refused).toBe('The parameter was not applied: Stretch (AnARAP): stretch along (su) must be positive, got -1');
  await expect(along).toHaveValue('1.4');
  const border = page.getByTestId(`op-falloff-${first.id}`);
  // (Leaving the amount field fires its own change, refused again: the border's refusal is waited for by its words.)
  const borderRefused = page.evaluate(() => new Promise((resolve) => {
    const off = window.anisoform.on('error', ({ message }) => {
      if (!message.startsWith('The region was not changed')) return;
      off();
      resolve(message);
    });
  }));
  await border.fill('-1');
  await border.dispatchEvent('change');
  expect(await borderRefused).toBe('The region was not changed: the region of Stretch (AnARAP): soft border (falloff) must be >= 0, got -1');
  await along.fill('');
  await along.dispatchEvent('change');
  await expect(along).toHaveValue('1.4');
  expect(await page.evaluate(() => window.anisoform.document().ops[0].op.transform.scale[0])).toBe(1.4);
  expect(await page.getByTestId('redo').getAttribute('title')).toBe('Redo Change the amounts of Twist (AnARAP) (Ctrl+Shift+Z)');
  expect(bitwise(await positions(), retwisted)).toBe(true);
  expect(pageErrors).toEqual([]);
});

test('an op deleted or moved in the Edits list: the later ops re-run, as a replay does; undo puts it back', async ({ page }) => {
  const pageErrors = await openApp(page);
  const { afterTwo, afterThree, document } = await editSpot(page);
  const [first, , third] = document.ops;
  const positions = () => evaluateBulk(page, () => Array.from(window.anisoform.positions()));
  const ids = () => page.evaluate(() => window.anisoform.document().ops.map((op) => op.id));
  const changed = async (action) => {
    const done = await armChange(page, 'document');
    await action();
    await done();
  };

  // The last op (Delete on its focused name, as its × does): the state before it, bitwise.
  await page.getByTestId(`op-select-${third.id}`).focus();
  await changed(() => page.keyboard.press('Delete'));
  expect(await ids()).toEqual([document.ops[0].id, document.ops[1].id]);
  await expect(page.getByTestId('op-list').locator('li')).toHaveCount(2);
  expect(bitwise(await positions(), afterTwo)).toBe(true);
  expect(await page.getByTestId('undo').getAttribute('title')).toBe('Undo Delete Shear (AnDefGrad) (Ctrl+Z)');
  await changed(() => page.evaluate(() => window.anisoform.undo()));
  expect(await ids()).toEqual(document.ops.map((op) => op.id));
  expect(bitwise(await positions(), afterThree)).toBe(true);

  // The first op: the two later ones re-run on the mesh as loaded; a replay
  // of the document without it gives the same positions.
  await changed(() => page.getByTestId(`op-delete-${first.id}`).click());
  const withoutFirst = { positions: await positions(), document: await page.evaluate(() => window.anisoform.document()) };
  expect(withoutFirst.document.ops.map((op) => op.id)).toEqual([document.ops[1].id, third.id]);
  expect(bitwise(withoutFirst.positions, afterThree)).toBe(false);
  await changed(() => page.evaluate((json) => window.anisoform.open(json), withoutFirst.document));
  expect(bitwise(await positions(), withoutFirst.positions)).toBe(true);

  // Moved up: the two re-run in their new order, as a replay of that order does; undo puts it back.
  await changed(() => page.evaluate((json) => window.anisoform.open(json), document));
  await page.getByTestId(`op-select-${third.id}`).click();
  await expect(page.getByTestId(`op-down-${third.id}`)).toBeDisabled();
  await changed(() => page.getByTestId(`op-up-${third.id}`).click());
  const reordered = { positions: await positions(), document: await page.evaluate(() => window.anisoform.document()) };
  expect(reordered.document.ops.map((op) => op.id)).toEqual([first.id, third.id, document.ops[1].id]);
  expect(bitwise(reordered.positions, afterThree)).toBe(false);
  expect(await page.getByTestId('undo').getAttribute('title')).toBe('Undo Move Shear (AnDefGrad) up (Ctrl+Z)');
  await changed(() => page.evaluate(() => window.anisoform.undo()));
  expect(await ids()).toEqual(document.ops.map((op) => op.id));
  expect(bitwise(await positions(), afterThree)).toBe(true);
  await changed(() => page.evaluate((json) => window.anisoform.open(json), reordered.document));
  expect(bitwise(await positions(), reordered.positions)).toBe(true);
  expect(await page.evaluate((id) => window.anisoform.moveOp(id, 3).catch((error) => error.message), first.id))
    .toMatch(/index must be an integer from 0 to 2, got 3/);
  expect(await page.evaluate((json) => window.anisoform.removeOp('op-99').catch((error) => error.message)))
    .toMatch(/no op 'op-99'/);
  expect(await page.evaluate(() => window.anisoform.moveOp('op-99', 0).catch((error) => error.message)))
    .toMatch(/no op 'op-99'/);
  expect(pageErrors).toEqual([]);
});

test("an earlier op's method and direction from the Edits list: it re-runs as a replay of the changed document does; undo takes each back", async ({ page }) => {
  const pageErrors = await openApp(page);
  const { afterThree, document } = await editSpot(page);
  const [first] = document.ops;
  const positions = () => evaluateBulk(page, () => Array.from(window.anisoform.positions()));
  const firstOp = () => page.evaluate(() => window.anisoform.document().ops[0]);
  const changed = async (action) => {
    const done = await armChange(page, 'document');
    await action();
    await done();
  };
  await page.getByTestId(`op-select-${first.id}`).click();
  const method = page.getByTestId(`op-method-${first.id}`);
  await expect(method).toHaveValue('anarap');
  await expect(page.getByTestId(`op-direction-${first.id}-z`)).toHaveValue('1');

  await changed(() => method.selectOption('andefgrad'));
  expect((await firstOp()).op.method).toBe('andefgrad');
  await expect(page.getByTestId(`op-select-${first.id}`)).toHaveText('Stretch (AnDefGrad)');
  const byAnDefGrad = await positions();
  expect(bitwise(byAnDefGrad, afterThree)).toBe(false);

  const x = page.getByTestId(`op-direction-${first.id}-x`);
  await changed(async () => {
    await x.fill('1');
    await x.press('Enter');
  });
  expect((await firstOp()).op.direction).toEqual({ type: 'global', vector: [1, 0, 1] });
  const tilted = await positions();
  expect(bitwise(tilted, byAnDefGrad)).toBe(false);
  const changedDocument = await page.evaluate(() => window.anisoform.document());

  expect(await page.getByTestId('undo').getAttribute('title')).toBe('Undo Change the direction of Stretch (AnDefGrad) (Ctrl+Z)');
  const undo = async () => changed(async () => expect(await page.evaluate(() => window.anisoform.undo())).toBe(true));
  await undo();
  expect(bitwise(await positions(), byAnDefGrad)).toBe(true);
  await undo();
  expect(bitwise(await positions(), afterThree)).toBe(true);
  expect((await firstOp()).label).toBe('Stretch (AnARAP)');

  // Refused, naming the problem: a screen drag, an empty patch, a method the core does not know.
  const refusal = (patch) => page.evaluate(([id, p]) => window.anisoform.setParameter(id, p).then(() => 'applied', (error) => error.message), [first.id, patch]);
  expect(await refusal({ direction: { type: 'screen', from: [0, 0], to: [1, 1] } })).toMatch(/screen drag cannot be stored/);
  expect(await refusal({})).toMatch(/changes nothing/);
  expect(await refusal({ method: 'magic' })).toMatch(/method/);
  // An ARAP drag is another kind of edit: it used to be taken, and the stretch vanished.
  expect(await refusal({ method: 'arap' })).toMatch(/method 'arap' is an ARAP drag, not a method of this op's transform/);
  expect(await refusal({ move: [0, 1, 0] })).toMatch(/move is an ARAP drag's; this op is anarap/);
  expect(await refusal({ transform: { scael: 2 } })).toMatch(/: Stretch \(AnARAP\): transform has an unknown field 'scael'/);
  expect(bitwise(await positions(), afterThree)).toBe(true);

  // The changed document replays to bitwise the positions the list gave.
  await changed(() => page.evaluate((json) => window.anisoform.open(json), changedDocument));
  expect(bitwise(await positions(), tilted)).toBe(true);
  expect(pageErrors).toEqual([]);
});

test('an op is renamed in the Edits list: saved with its edits, undone as a step, nothing re-runs', async ({ page }) => {
  const pageErrors = await openApp(page);
  const { afterThree, document } = await editSpot(page);
  const [first] = document.ops;
  const opener = page.getByTestId(`op-select-${first.id}`);
  await opener.click();
  await expect(opener).toHaveAttribute('aria-expanded', 'true');
  const name = page.getByTestId(`op-name-${first.id}`);
  await expect(name).toHaveValue('Stretch (AnARAP)');
  await name.fill('  Longer nose  ');
  await name.press('Enter');
  await expect(page.getByTestId(`op-select-${first.id}`)).toHaveText('Longer nose');
  const renamed = await evaluateBulk(page, () => ({ positions: Array.from(window.anisoform.positions()),
    label: window.anisoform.document().ops[0].label }));
  expect(renamed.label).toBe('Longer nose');
  expect(bitwise(renamed.positions, afterThree)).toBe(true);
  expect(await page.getByTestId('undo').getAttribute('title')).toBe('Undo Rename Stretch (AnARAP) to Longer nose (Ctrl+Z)');
  // Esc puts the name back; an empty name is no name.
  await name.fill('Something else');
  await name.press('Escape');
  await expect(name).toHaveValue('Longer nose');
  expect(await page.evaluate((id) => window.anisoform.renameOp(id, ' ').catch((error) => error.code), first.id)).toBe('bad-parameter');
  await page.evaluate(() => window.anisoform.undo());
  await expect(page.getByTestId(`op-select-${first.id}`)).toHaveText('Stretch (AnARAP)');
  expect(pageErrors).toEqual([]);
});

test('a direction in the Edits list goes from z to x whatever field is typed first', async ({ page }) => {
  const pageErrors = await openApp(page);
  const { document } = await editSpot(page);
  const [first] = document.ops;
  await page.getByTestId(`op-select-${first.id}`).click();
  const z = page.getByTestId(`op-direction-${first.id}-z`);
  await expect(z).toHaveAccessibleName('Direction z');
  // z to 0 first: (0, 0, 0) is no direction; nothing is sent, and the fields keep what was typed.
  await z.fill('0');
  await z.press('Tab');
  await expect(page.getByTestId(`op-direction-${first.id}-hint`)).toContainText('needs a component that is not 0');
  await expect(z).toHaveValue('0');
  await expect(page.getByTestId('error')).toBeHidden();
  expect((await page.evaluate(() => window.anisoform.document().ops[0])).op.direction.vector).toEqual([0, 0, 1]);
  const done = await armChange(page, 'document');
  const x = page.getByTestId(`op-direction-${first.id}-x`);
  await x.fill('1');
  await x.press('Enter');
  await done();
  expect((await page.evaluate(() => window.anisoform.document().ops[0])).op.direction).toEqual({ type: 'global', vector: [1, 0, 0] });
  await expect(page.getByTestId(`op-direction-${first.id}-hint`)).toBeEmpty();
  expect(pageErrors).toEqual([]);
});

test("an ARAP drag's move from the Edits list: the dragged part moves by the new offset; undo takes it back", async ({ page }) => {
  const pageErrors = await openApp(page);
  const { rest, dragged } = await evaluateBulk(page, async () => {
    const api = window.anisoform;
    const rest = Array.from(api.positions());
    await api.select({ box: { min: [-1, 0.5, -1], max: [1, 2, 1] } });
    const selection = api.selection();
    await api.deform({ method: 'arap', move: [0, 0.2, 0] });
    return { rest, dragged: selection.findIndex((weight) => weight === 1) };
  });
  const op = (await page.evaluate(() => window.anisoform.document().ops[0]));
  expect(op.label).toBe('Move (ARAP)');
  await page.getByTestId(`op-select-${op.id}`).click();
  // No method or direction: ARAP with handles moves the part by its offset.
  await expect(page.getByTestId(`op-move-${op.id}-y`)).toHaveValue('0.2');
  await expect(page.getByTestId(`op-method-${op.id}`)).toHaveCount(0);
  await expect(page.getByTestId(`op-direction-${op.id}-x`)).toHaveCount(0);
  const moved = async () => evaluateBulk(page, (i) => Array.from(window.anisoform.positions().slice(3 * i, 3 * i + 3)), dragged);
  const y = page.getByTestId(`op-move-${op.id}-y`);
  const changed = await armChange(page, 'document');
  await y.fill('0.4');
  await y.press('Enter');
  await changed();
  expect((await page.evaluate(() => window.anisoform.document().ops[0].op.move))).toEqual([0, 0.4, 0]);
  const offset = (await moved()).map((value, axis) => value - rest[3 * dragged + axis]);
  expect(offset[0]).toBeCloseTo(0, 5);
  expect(offset[1]).toBeCloseTo(0.4, 5);
  expect(offset[2]).toBeCloseTo(0, 5);
  const undone = await armChange(page, 'document');
  expect(await page.evaluate(() => window.anisoform.undo())).toBe(true);
  await undone();
  expect((await moved())[1] - rest[3 * dragged + 1]).toBeCloseTo(0.2, 5);
  expect(pageErrors).toEqual([]);
});

test('an amount typed in the last edit previews live; leaving the field commits it, or, typed back, shows the committed shape again', async ({ page }) => {
  const pageErrors = await openApp(page);
  const { afterThree, document } = await editSpot(page);
  const [, second, third] = document.ops;
  const shear = () => page.evaluate(() => window.anisoform.document().ops[2].op.transform.shear);
  await page.evaluate(() => {
    window.__live = 0;
    window.anisoform.on('positions', ({ live, positions }) => {
      if (live) window.__live++;
      window.__shown = { live, positions: Array.from(positions) };
    });
  });
  const typeInto = async (field, text) => {
    await field.click();
    await field.press('Control+a');
    await page.keyboard.type(text);
  };

  // An earlier edit: no preview while typing (it would replay the later ones).
  await page.getByTestId(`op-select-${second.id}`).click();
  const rate = page.getByTestId(`op-amount-${second.id}-Twist (degrees/unit)`);
  await typeInto(rate, '60');
  await page.waitForTimeout(500);
  expect(await page.evaluate(() => window.__live)).toBe(0);
  await rate.fill('30'); // its own value again: nothing to commit
  await rate.blur();

  // The last edit: typing 0.6, the shape follows live (the document keeps 0.3).
  await page.getByTestId(`op-select-${third.id}`).click();
  const amount = page.getByTestId(`op-amount-${third.id}-Shear`);
  await expect(amount).toHaveValue('0.3');
  // (Opening the edit showed its region, with no step of its own.)
  await expect(page.getByTestId(`op-region-${third.id}`)).toContainText('shown on the mesh');
  const undoTitle = await page.getByTestId('undo').getAttribute('title');
  expect(undoTitle).toBe('Undo Shear (AnDefGrad) (Ctrl+Z)');
  await typeInto(amount, '0.6');
  await expect.poll(() => page.evaluate(() => window.__live)).toBeGreaterThan(0);
  expect(await shear()).toBe(0.3);
  // Typed back to 0.3 and left: no change, and the committed shape comes back, bitwise.
  await typeInto(amount, '0.3');
  const back = await armChange(page, 'document');
  await amount.blur();
  await back();
  const shown = await page.evaluate(() => window.__shown);
  expect(shown.live).toBe(false);
  expect(bitwise(shown.positions, afterThree)).toBe(true);
  expect(await shear()).toBe(0.3);
  expect(await page.getByTestId('undo').getAttribute('title')).toBe(undoTitle);

  // Typed and left with a new value: committed, a step of the history.
  await typeInto(amount, '0.45');
  const committed = await armChange(page, 'document');
  await amount.press('Tab');
  await committed();
  expect(await shear()).toBe(0.45);
  expect(await page.getByTestId('undo').getAttribute('title')).toBe('Undo Change the amounts of Shear (AnDefGrad) (Ctrl+Z)');
  expect(pageErrors).toEqual([]);
});

test('the Edits list by keyboard: Esc takes a typed amount back, a decimal comma is a point, and the focus stays where it was', async ({ page }) => {
  const pageErrors = await openApp(page);
  const { afterThree, document } = await editSpot(page);
  const [first, second, third] = document.ops;
  const shear = () => page.evaluate(() => window.anisoform.document().ops.at(-1).op.transform.shear);
  const focused = () => page.evaluate(() => window.document.activeElement?.getAttribute('data-testid') ?? window.document.activeElement?.tagName);
  await page.evaluate(() => {
    window.anisoform.on('positions', ({ live, positions }) => {
      window.__shown = { live, positions: Array.from(positions) };
    });
  });

  // Enter on an op's name opens it, and the focus stays on the name.
  await page.getByTestId(`op-select-${third.id}`).focus();
  await page.keyboard.press('Enter');
  const amount = page.getByTestId(`op-amount-${third.id}-Shear`);
  await expect(amount).toHaveValue('0.3');
  expect(await focused()).toBe(`op-select-${third.id}`);
  // (Opening the op shows its region, with no step of the history.)
  await expect(page.getByTestId(`op-region-${third.id}`)).toContainText('shown on the mesh');
  const undoTitle = await page.getByTestId('undo').getAttribute('title');
  expect(undoTitle).toBe('Undo Shear (AnDefGrad) (Ctrl+Z)');

  // Typed 0.9 (previewed live), then Esc: the field shows 0.3 and the committed shape is back, bitwise; leaving commits nothing.
  await amount.focus();
  await amount.press('Control+a');
  await page.keyboard.type('0.9');
  await expect.poll(() => page.evaluate(() => window.__shown?.live)).toBe(true);
  await page.keyboard.press('Escape');
  await expect(amount).toHaveValue('0.3');
  await expect.poll(() => page.evaluate(() => window.__shown.live)).toBe(false);
  expect(bitwise(await page.evaluate(() => window.__shown.positions), afterThree)).toBe(true);
  await amount.blur();
  await page.waitForTimeout(300);
  expect(await shear()).toBe(0.3);
  expect(await page.getByTestId('undo').getAttribute('title')).toBe(undoTitle);

  // "0,45" typed (a decimal comma) and Enter: 0.45, not 45; the focus stays in the field.
  await amount.focus();
  await amount.press('Control+a');
  await page.keyboard.type('0,45');
  const committed = await armChange(page, 'document');
  await page.keyboard.press('Enter');
  await committed();
  expect(await shear()).toBe(0.45);
  expect(await focused()).toBe(`op-amount-${third.id}-Shear`);

  // Move down by keyboard on the first op: the focus stays on its Move down button; at the bottom, on its name.
  await page.getByTestId(`op-select-${first.id}`).click();
  await page.getByTestId(`op-down-${first.id}`).focus();
  let moved = await armChange(page, 'document');
  await page.keyboard.press('Enter');
  await moved();
  expect(await focused()).toBe(`op-down-${first.id}`);
  moved = await armChange(page, 'document');
  await page.keyboard.press('Enter');
  await moved();
  expect(await page.evaluate(() => window.anisoform.document().ops.map((entry) => entry.id))).toEqual([second.id, third.id, first.id]);
  expect(await focused()).toBe(`op-select-${first.id}`);

  // Delete on the name of the middle op: the focus goes to the name now in its place.
  await page.getByTestId(`op-select-${third.id}`).focus();
  const deleted = await armChange(page, 'document');
  await page.keyboard.press('Delete');
  await deleted();
  expect(await focused()).toBe(`op-select-${first.id}`);
  expect(pageErrors).toEqual([]);
});

test("an op's region shows on the mesh and the current selection replaces it; the result replays bitwise", async ({ page, browser }) => {
  const pageErrors = await openApp(page);
  // The first op's region as the core selects it on the mesh as loaded (its input).
  const firstRegion = await evaluateBulk(page, async () => {
    await window.anisoform.select({ sphere: { center: [0, 0.3, 0.5], radius: 0.4 } }, { falloff: 0.2 });
    return Array.from(window.anisoform.selection());
  });
  const { afterThree, document } = await editSpot(page);
  const [first] = document.ops;

  // Opening the op shows its region on the mesh (its count, though the mesh has moved since), and leaves
  // the selection and the history as they were: a selection made before opening it can replace its region.
  const box = { min: [-1, 0, -1], max: [1, 1, 1] };
  const selectedBefore = await page.evaluate((region) => window.anisoform.select({ box: region }, { falloff: 0.1 }), box);
  const undoTitle = await page.getByTestId('undo').getAttribute('title');
  await page.getByTestId(`op-select-${first.id}`).click();
  const regionCount = firstRegion.filter((w) => w > 0).length;
  await expect(page.getByTestId(`op-region-${first.id}`))
    .toHaveText(`Region: ${first.region} (${regionCount.toLocaleString('en-US')} vertices, shown on the mesh)`);
  expect(await page.evaluate(() => window.anisoform.selection().filter((w) => w > 0).length)).toBe(selectedBefore);
  expect(await page.getByTestId('undo').getAttribute('title')).toBe(undoTitle);

  // That selection becomes the op's region; the op and the later ones re-run.
  const rerun = await armChange(page, 'document');
  await page.getByTestId(`op-use-selection-${first.id}`).click();
  await rerun();
  const changed = await evaluateBulk(page, () => ({ positions: Array.from(window.anisoform.positions()),
    document: window.anisoform.document() }));
  const region = changed.document.regions.find((r) => r.name === changed.document.ops[0].region);
  expect(changed.document.ops[0].region).not.toBe(first.region);
  expect(region.steps).toEqual([{ region: { box }, falloff: 0.1 }]);
  expect(changed.document.ops.slice(1)).toEqual(document.ops.slice(1));
  // The op's new region is shown in its place, with its count.
  await expect(page.getByTestId(`op-region-${first.id}`))
    .toHaveText(new RegExp(`^Region: ${region.name} \\([\\d,]+ vertices, shown on the mesh\\)$`));
  expect(bitwise(changed.positions, afterThree)).toBe(false);

  // A fresh page replays the new document to bitwise the same positions.
  const fresh = await browser.newPage();
  const freshErrors = await openApp(fresh);
  const replayed = await evaluateBulk(fresh, async (json) => {
    await window.anisoform.open(json);
    return Array.from(window.anisoform.positions());
  }, changed.document);
  expect(bitwise(replayed, changed.positions)).toBe(true);
  await fresh.close();

  // A wider soft border: the op's region is the same box with the new falloff; undo takes it back.
  const falloff = page.getByTestId(`op-falloff-${first.id}`);
  await expect(falloff).toHaveValue('0.1');
  const softer = await armChange(page, 'document');
  await falloff.fill('0.3');
  await falloff.press('Enter');
  await softer();
  const widened = await evaluateBulk(page, () => ({ positions: Array.from(window.anisoform.positions()), document: window.anisoform.document() }));
  const widenedRegion = widened.document.regions.find((r) => r.name === widened.document.ops[0].region);
  expect(widenedRegion.steps).toEqual([{ region: { box }, falloff: 0.3 }]);
  expect(bitwise(widened.positions, changed.positions)).toBe(false);
  expect(await page.getByTestId('undo').getAttribute('title')).toBe('Undo Change the region of Stretch (AnARAP) (Ctrl+Z)');
  await expect(page.getByTestId(`op-region-${first.id}`))
    .toHaveText(new RegExp(`^Region: ${widened.document.ops[0].region} \\([\\d,]+ vertices, shown on the mesh\\)$`));
  const undone = await armChange(page, 'document');
  expect(await page.evaluate(() => window.anisoform.undo())).toBe(true);
  await undone();
  expect(bitwise(await evaluateBulk(page, () => Array.from(window.anisoform.positions())), changed.positions)).toBe(true);
  expect(await page.evaluate(() => window.anisoform.setRegion('op-1', []).catch((error) => error.message)))
    .toMatch(/steps must be a list of select steps/);
  expect(pageErrors).toEqual([]);
  expect(freshErrors).toEqual([]);
});

test('the work is autosaved and restored bitwise after a reload; reset clears the edits, the mesh stays', async ({ page }) => {
  const pageErrors = await openApp(page);
  const { afterThree, document } = await editSpot(page);
  // The autosave of the last op is written after the commit resolves.
  await expect.poll(() => savedWork(page).then((record) => record?.document.ops.length ?? 0)).toBe(3);

  await page.reload();
  await page.evaluate(() => window.anisoform.ready);
  const restored = await evaluateBulk(page, () => ({ positions: Array.from(window.anisoform.positions()),
    document: window.anisoform.document() }));
  expect(restored.document.ops).toEqual(document.ops);
  expect(bitwise(restored.positions, afterThree)).toBe(true);

  const loaded = await evaluateBulk(page, () => {
    window.anisoform.reset();
    return Array.from(window.anisoform.positions());
  });
  await page.waitForTimeout(300);
  await page.reload();
  await page.evaluate(() => window.anisoform.ready);
  const afterReset = await evaluateBulk(page, () => ({ positions: Array.from(window.anisoform.positions()),
    ops: window.anisoform.document().ops.length }));
  expect(afterReset.ops).toBe(0);
  expect(bitwise(afterReset.positions, loaded)).toBe(true);

  // A mesh of the user's, edited and reset: a reload shows it without the
  // edits (it used to bring the default mesh back).
  expect((await uploadFile(page, meshPath('closed/torus.obj'))).ok).toBe(true);
  const torus = await evaluateBulk(page, async () => {
    const api = window.anisoform;
    const before = Array.from(api.positions());
    await api.select({ all: true });
    await api.deform({ method: 'anarap', direction: { type: 'global', vector: [1, 0, 0] }, transform: { scale: [1.3, 1] } });
    api.reset();
    return before;
  });
  await expect.poll(() => savedWork(page).then((record) => record && `${record.meshName} ${record.document.ops.length}`)).toBe('torus.obj 0');
  await page.reload();
  await page.evaluate(() => window.anisoform.ready);
  const reloaded = await evaluateBulk(page, () => ({ name: window.anisoform.document().mesh.name,
    positions: Array.from(window.anisoform.positions()), ops: window.anisoform.document().ops.length }));
  expect(reloaded.name).toBe('torus.obj');
  expect(reloaded.ops).toBe(0);
  expect(bitwise(reloaded.positions, torus)).toBe(true);
  expect(pageErrors).toEqual([]);
});

test('a restore of the autosaved work stopped with Esc says the edits stay saved, and a reload puts them back', async ({ page }) => {
  // The notice said "the mesh and its history are as they were" with no
  // edit left, and the next edit saved over all of them.
  const pageErrors = await openApp(page);
  const document = await page.evaluate(async () => {
    const api = window.anisoform;
    await api.select({ sphere: { center: [0, 0.3, 0.5], radius: 0.4 } });
    await api.deform({ method: 'anarap', direction: { type: 'global', vector: [0, 0, 1] }, transform: { scale: [1.4, 1] } });
    await api.deform({ method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: [1.2, 1] } });
    return api.document();
  });
  await expect.poll(() => savedWork(page).then((record) => record?.document.ops.length ?? 0)).toBe(2);
  const selection = await evaluateBulk(page, () => Array.from(window.anisoform.selection()));
  await expect.poll(() => savedView(page).then((view) => view?.work.ops.length === 2 && view.selection !== null)).toBe(true);
  // Cancelled once the first saved edit's replay is sent to the worker (the
  // first reload only). Not on its progress: a solve under 150 ms shows none,
  // and on a fast machine the restore then ended before any cancel.
  await page.addInitScript(() => {
    if (sessionStorage.getItem('restore-cancelled')) return;
    const post = Worker.prototype.postMessage;
    Worker.prototype.postMessage = function postMessage(message, ...rest) {
      const result = post.call(this, message, ...rest);
      if (message?.kind === 'replay' && /^Edit 1 of 2/.test(message.label ?? '') && !sessionStorage.getItem('restore-cancelled')) {
        sessionStorage.setItem('restore-cancelled', '1');
        // After the client has recorded the request as in flight.
        queueMicrotask(() => window.anisoform.cancel());
      }
      return result;
    };
  });
  await page.reload();
  await page.evaluate(() => window.anisoform.ready);
  await expect(page.getByTestId('notice')).toContainText('Putting back the saved work was stopped: its 2 edits stay saved');
  expect(await page.evaluate(() => window.anisoform.document().ops.length)).toBe(0);
  // The selection saved with the two edits is not put on the work without them.
  expect(await page.evaluate(() => window.anisoform.selection().every((weight) => weight === 0))).toBe(true);
  expect((await savedWork(page)).document.ops.length).toBe(2);
  await page.reload();
  await page.evaluate(() => window.anisoform.ready);
  expect(await page.evaluate(() => window.anisoform.document().ops)).toEqual(document.ops);
  expect(bitwise(await evaluateBulk(page, () => Array.from(window.anisoform.selection())), selection)).toBe(true);
  expect(pageErrors).toEqual([]);
});

const closeTo = (values) => values.map((value) => expect.closeTo(value, 9));

// A reload brought back the mesh and the edits only: the selected region,
// the tool, its amounts, the direction, method and brush, and the view were
// gone (the selection empty, the Select tool, the defaults, the camera framed).
test('a reload puts back the selection, the tool and its settings and the camera; Apply and Undo go on from them', async ({ page }) => {
  const pageErrors = await openApp(page);
  await page.evaluate(() => window.anisoform.select({ sphere: { center: [0, 0.3, 0.5], radius: 0.4 } }, { falloff: 0.2 }));
  const type = async (field, value) => {
    await page.locator(field).fill(value);
    await page.locator(field).press('Tab');
  };
  await type('#brush-radiusPercent', '12');
  await page.getByTestId('tool-stretch').click();
  await type('#stretch-along', '1.3');
  await type('#stretch-across', '0.9');
  await page.locator('#direction-source').selectOption('global');
  await page.locator('#direction-axis').selectOption('y');
  await page.locator('#solver-method').selectOption('andefgrad');
  await type('#solver-iterations', '30');
  // Orbited, zoomed and panned by key.
  await page.getByTestId('viewport').focus();
  for (const key of ['Shift+ArrowLeft', 'Shift+ArrowLeft', 'Shift+ArrowUp', '+', '+', 'ArrowLeft']) await page.keyboard.press(key);
  await page.getByTestId('apply-stretch').click();
  await expect.poll(() => page.evaluate(() => window.anisoform.document().ops.length)).toBe(1);
  const before = await evaluateBulk(page, () => ({ selection: Array.from(window.anisoform.selection()), camera: window.anisoform.camera(),
    positions: Array.from(window.anisoform.positions()), document: window.anisoform.document() }));
  expect(before.document.ops[0].op).toMatchObject({ method: 'andefgrad', maxIterations: 30, transform: { scale: [1.3, 0.9] } });
  await expect.poll(() => savedView(page).then((view) => view?.work.ops.length === 1
    && view.camera.position.every((value, k) => value === before.camera.position[k]))).toBe(true);

  await page.reload();
  await page.evaluate(() => window.anisoform.ready);
  const after = await evaluateBulk(page, () => ({ selection: Array.from(window.anisoform.selection()), camera: window.anisoform.camera(),
    positions: Array.from(window.anisoform.positions()) }));
  expect(bitwise(after.positions, before.positions)).toBe(true);
  expect(bitwise(after.selection, before.selection)).toBe(true);
  expect(after.selection.filter((weight) => weight > 0 && weight < 1).length).toBeGreaterThan(0); // the soft border too
  for (const key of ['position', 'target', 'view', 'projection']) expect(after.camera[key]).toEqual(closeTo(before.camera[key]));
  await expect(page.getByTestId('tool-stretch')).toHaveAttribute('aria-pressed', 'true');
  await expect(page.locator('#stretch-along')).toHaveValue('1.3');
  await expect(page.locator('#stretch-across')).toHaveValue('0.9');
  await expect(page.locator('#direction-source')).toHaveValue('global');
  await expect(page.locator('#direction-axis')).toHaveValue('y');
  await expect(page.locator('#solver-method')).toHaveValue('andefgrad');
  await expect(page.locator('#solver-iterations')).toHaveValue('30');
  await expect(page.locator('#brush-radiusPercent')).toHaveValue('12');
  // Undo takes back the edit (not the selection put back), and Apply makes
  // the same edit on the selection put back.
  const undo = page.getByTestId('undo');
  await expect(undo).toHaveAttribute('title', `Undo ${before.document.ops[0].label} (Ctrl+Z)`);
  await page.getByTestId('apply-stretch').click();
  await expect.poll(() => page.evaluate(() => window.anisoform.document().ops.length)).toBe(2);
  const applied = await page.evaluate(() => window.anisoform.document());
  expect(applied.ops[1].op).toEqual(before.document.ops[0].op);
  const region = applied.regions.find((r) => r.name === applied.ops[1].region).steps[0].region;
  expect(region.vertices).toEqual(before.selection.flatMap((weight, i) => (weight > 0 ? [i] : [])));
  expect(region.weights).toEqual(closeTo(before.selection.filter((weight) => weight > 0)));
  expect(bitwise(await evaluateBulk(page, () => Array.from(window.anisoform.positions())), before.positions)).toBe(false);
  await undo.click();
  await expect.poll(() => page.evaluate(() => window.anisoform.document().ops.length)).toBe(1);
  expect(bitwise(await evaluateBulk(page, () => Array.from(window.anisoform.positions())), before.positions)).toBe(true);

  // An orbit and a selection made just before a reload (within the view's
  // 250 ms wait) come back too: they were lost, the view before them shown.
  await expect.poll(() => savedWork(page).then((record) => record?.document.ops.length)).toBe(1);
  await page.getByTestId('viewport').focus();
  for (const key of ['Shift+ArrowRight', 'Shift+ArrowRight', 'Shift+ArrowRight']) await page.keyboard.press(key);
  const last = await evaluateBulk(page, async () => {
    await window.anisoform.select({ sphere: { center: [0, -0.2, 0.3], radius: 0.3 } });
    return { selection: Array.from(window.anisoform.selection()), camera: window.anisoform.camera() };
  });
  await page.reload();
  await page.evaluate(() => window.anisoform.ready);
  const restored = await evaluateBulk(page, () => ({ selection: Array.from(window.anisoform.selection()), camera: window.anisoform.camera() }));
  expect(bitwise(restored.selection, last.selection)).toBe(true);
  for (const key of ['position', 'target']) expect(restored.camera[key]).toEqual(closeTo(last.camera[key]));
  expect(pageErrors).toEqual([]);
});

test("two tabs keep their own autosaved work: a reload restores its own tab's, a new tab the latest", async ({ context }) => {
  // One record for all tabs: a reload of one brought back the other's mesh
  // and edits, and its own were gone. (The tabs of one context share the
  // storage; the `page` fixture may come from another.)
  const page = await context.newPage();
  const pageErrors = await openApp(page, { navigate: true });
  const stretch = (target) => target.evaluate(async () => {
    const api = window.anisoform;
    await api.select({ all: true });
    await api.deform({ method: 'anarap', direction: { type: 'global', vector: [1, 0, 0] }, transform: { scale: [1.2, 1] } });
  });
  await stretch(page);
  const spotName = await page.evaluate(() => window.anisoform.document().mesh.name);
  const other = await context.newPage();
  const otherErrors = await openApp(other, { navigate: true });
  expect((await uploadFile(other, meshPath('closed/torus.obj'))).ok).toBe(true);
  await stretch(other);
  await expect.poll(() => savedWork(other).then((record) => record && `${record.meshName} ${record.document.ops.length}`))
    .toBe('torus.obj 1');
  await stretch(page); // the first tab saves last
  await expect.poll(() => savedWork(page).then((record) => record && `${record.meshName} ${record.document.ops.length}`))
    .toBe(`${spotName} 2`);

  const work = (target) => target.evaluate(() => `${window.anisoform.document().mesh.name} ${window.anisoform.document().ops.length}`);
  const third = await context.newPage();
  await openApp(third, { navigate: true });
  expect(await work(third)).toBe(`${spotName} 2`);
  await other.reload();
  await other.evaluate(() => window.anisoform.ready);
  expect(await work(other)).toBe('torus.obj 1');

  // A tab opened from the page starts with a copy of its sessionStorage (its
  // id): it shows a copy of the work, then saves apart (the two shared one
  // record, and a reload brought back the other tab's mesh).
  const [twin] = await Promise.all([context.waitForEvent('page'), page.evaluate(() => window.open(location.href))]);
  await twin.waitForFunction(() => window.anisoform?.ready);
  await twin.evaluate(() => window.anisoform.ready);
  expect(await work(twin)).toBe(`${spotName} 2`);
  await stretch(twin);
  await expect.poll(() => work(twin)).toBe(`${spotName} 3`);
  await page.waitForTimeout(500); // its autosave written
  await page.reload();
  await page.evaluate(() => window.anisoform.ready);
  expect(await work(page)).toBe(`${spotName} 2`);
  expect(pageErrors).toEqual([]);
  expect(otherErrors).toEqual([]);
});

test("undo called again on each step's 'document' event takes back several steps, as the API says", async ({ page }) => {
  // The event came while the step's re-run still ran: the next undo() was
  // refused as busy ("Undo waits until the solve has ended").
  const pageErrors = await openApp(page);
  const outcome = await page.evaluate(async () => {
    const api = window.anisoform;
    // Three edits of one selection, the first then turned off: four steps
    // that each change the document.
    await api.select({ sphere: { center: [0, 0.3, 0.5], radius: 0.4 } });
    for (const vector of [[0, 0, 1], [0, 1, 0], [1, 0, 0]]) {
      await api.deform({ method: 'anarap', direction: { type: 'global', vector }, transform: { scale: [1.2, 1] } });
    }
    await api.setOpEnabled(api.document().ops[0].id, false);
    const answers = [];
    const ended = new Promise((resolve) => {
      const off = api.on('document', (current) => {
        if (current.ops.length === 1) {
          off();
          resolve();
          return;
        }
        answers.push(api.undo());
      });
    });
    answers.push(api.undo());
    await ended;
    return { answers, ops: api.document().ops.map((op) => op.enabled) };
  });
  // Turned back on, then the third op and the second taken away.
  expect(outcome.answers).toEqual([true, true, true]);
  expect(outcome.ops).toEqual([true]);
  await expect(page.getByTestId('notice')).toBeHidden();
  expect(pageErrors).toEqual([]);
});

test('after a reload, undo first turns back on an op that was off, then takes the ops away', async ({ page }) => {
  const pageErrors = await openApp(page);
  const { afterTwo, afterThree, document } = await editSpot(page);
  const second = document.ops[1];
  await page.evaluate((id) => window.anisoform.setOpEnabled(id, false), second.id);
  await expect.poll(() => savedWork(page).then((record) => record?.document.ops[1].enabled)).toBe(false);

  await page.reload();
  await page.evaluate(() => window.anisoform.ready);
  const undo = page.getByTestId('undo');
  await expect(undo).toHaveAttribute('title', `Undo Turn off ${second.label} (Ctrl+Z)`);
  await undo.click();
  await expect.poll(() => page.evaluate(() => window.anisoform.document().ops.map((op) => op.enabled)))
    .toEqual([true, true, true]);
  await expect.poll(async () => bitwise(await evaluateBulk(page, () => Array.from(window.anisoform.positions())), afterThree))
    .toBe(true);
  await expect(undo).toHaveAttribute('title', `Undo ${document.ops[2].label} (Ctrl+Z)`);
  await undo.click();
  await expect.poll(async () => bitwise(await evaluateBulk(page, () => Array.from(window.anisoform.positions())), afterTwo))
    .toBe(true);
  // Redo turns it off again, as the session that made it had.
  const redo = page.getByTestId('redo');
  await redo.click();
  await redo.click();
  await expect.poll(() => page.evaluate(() => window.anisoform.document().ops.map((op) => op.enabled)))
    .toEqual([true, false, true]);
  expect(pageErrors).toEqual([]);
});

test('a full storage quota is reported and the work in the page is kept', async ({ page }) => {
  const pageErrors = await openApp(page);
  const outcome = await page.evaluate(async () => {
    const api = window.anisoform;
    // The browser refuses every write, as with a full quota (until the end
    // of this evaluation: the next test's app starts in this page).
    const { put } = IDBObjectStore.prototype;
    IDBObjectStore.prototype.put = () => {
      throw new DOMException('The quota has been exceeded.', 'QuotaExceededError');
    };
    const reported = new Promise((resolve) => {
      const off = api.on('error', (event) => {
        off();
        resolve(event);
      });
    });
    await api.select({ all: true });
    try {
      await api.deform({ method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: [1.2, 1] } });
      return { error: await reported, ops: api.document().ops.length };
    } finally {
      IDBObjectStore.prototype.put = put;
    }
  });
  expect(outcome.error.code).toBe('storage');
  expect(outcome.error.message).toContain('quota');
  expect(outcome.error.message).toContain('Your work in this page is kept');
  expect(outcome.ops).toBe(1);
  await expect(page.getByTestId('error')).toContainText('quota');
  expect(pageErrors).toEqual([]);
});

test('a bad document is refused with its code and the work is kept', async ({ page }) => {
  const pageErrors = await openApp(page);
  const { afterThree, document } = await editSpot(page);
  const refusals = await evaluateBulk(page, async (good) => {
    const api = window.anisoform;
    const outcomes = [];
    const cases = [
      { ...good, version: 7 },
      { ...good, ops: [{ ...good.ops[0], region: 'nowhere' }] },
      { ...good, ops: [{ ...good.ops[0], op: { ...good.ops[0].op, transform: { scale: [-1, 1] } } }] },
      { ...good, mesh: { ...good.mesh, hash: 'fnv1a64:0000000000000000' } },
    ];
    for (const json of cases) {
      try {
        await api.open(json);
        outcomes.push('opened');
      } catch (error) {
        outcomes.push({ code: error.code, message: error.message });
      }
    }
    return { outcomes, positions: Array.from(api.positions()), ops: api.document().ops.length };
  }, document);
  expect(refusals.outcomes.map((o) => o.code)).toEqual(['bad-parameter', 'bad-parameter', 'bad-parameter', 'bad-mesh']);
  expect(refusals.outcomes[0].message).toContain('document.version is 7, which this build does not read');
  expect(refusals.outcomes[1].message).toContain("names region 'nowhere'");
  expect(refusals.outcomes[2].message).toContain(`document.ops[0] (id '${document.ops[0].id}').op.transform`);
  expect(refusals.outcomes[3].message).toContain('does not match the loaded mesh');
  await expect(page.getByTestId('error')).toContainText('does not match the loaded mesh');
  expect(refusals.ops).toBe(3);
  expect(bitwise(refusals.positions, afterThree)).toBe(true);
  // The good document opened after them puts the refusal behind, and the
  // status bar shows its last solve (the error stayed over the opened edits).
  await page.evaluate((good) => window.anisoform.open(good), document);
  await expect(page.getByTestId('error')).toBeHidden();
  await expect(page.getByTestId('status-solve')).toHaveText(/^solve [\d.]+ ms · \d+ it/);

  // With other mesh bytes: the mesh is loaded, the hash refuses, and the
  // work (Spot and its three ops) comes back.
  // As base64 text: an array of 200k numbers takes seconds to cross to the page.
  const knot = readFileSync(meshPath('closed/knot1.off')).toString('base64');
  const withOtherMesh = await page.evaluate(async ({ good, bytes }) => {
    const api = window.anisoform;
    let code = null;
    let message = null;
    try {
      await api.open({ ...good, mesh: { ...good.mesh, name: 'knot1.off' } }, Uint8Array.from(atob(bytes), (c) => c.charCodeAt(0)));
    } catch (error) {
      ({ code, message } = error);
    }
    return { code, message, positions: Array.from(api.positions()), ops: api.document().ops.length, vertices: api.info().vertices };
  }, { good: document, bytes: knot });
  expect(withOtherMesh.code).toBe('bad-mesh');
  // The file given is named: "the loaded mesh" read as the one on screen, which is Spot again.
  expect(withOtherMesh.message).toMatch(/does not match the mesh of knot1\.off fnv1a64:[0-9a-f]{16} \(\d+ vertices/);
  expect(withOtherMesh.ops).toBe(3);
  expect(bitwise(withOtherMesh.positions, afterThree)).toBe(true);
  expect(pageErrors).toEqual([]);
});

test('a slider on the last op updates the shape live at 20k vertices', { tag: '@speed' }, async ({ page }) => {
  test.setTimeout(120_000);
  const pageErrors = await openApp(page);
  const loaded = await uploadFile(page, meshPath('closed/armadillo.off'));
  expect(loaded.ok).toBe(true);
  expect(loaded.info.vertices).toBeGreaterThanOrEqual(20_000);
  const measured = await page.evaluate(async () => {
    const api = window.anisoform;
    const { min, max } = (() => {
      const p = api.positions();
      const lo = [Infinity, Infinity, Infinity];
      const hi = [-Infinity, -Infinity, -Infinity];
      for (let i = 0; i < p.length; i++) {
        lo[i % 3] = Math.min(lo[i % 3], p[i]);
        hi[i % 3] = Math.max(hi[i % 3], p[i]);
      }
      return { min: lo, max: hi };
    })();
    const top = [...min];
    top[1] = min[1] + 0.6 * (max[1] - min[1]);
    await api.select({ box: { min: top, max } }, { falloff: 0.1 * (max[1] - min[1]) });
    await api.deform({ method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: [1.1, 1] } });
    const opId = api.document().ops[0].id;

    // A 2 s drag: a slider value per animation frame; a frame counts when
    // positions it had not shown yet arrived since the previous frame.
    let arrived = 0;
    const arrivals = [];
    const off = api.on('positions', ({ live }) => {
      if (!live) return;
      arrived++;
      arrivals.push(performance.now());
    });
    let seen = 0;
    let changedFrames = 0;
    // What the viewport draws while the slider moves (viewer/interaction-proxy.js).
    const canvas = document.querySelector('canvas[data-testid="viewport"]');
    const details = new Set();
    const start = performance.now();
    await new Promise((resolve) => {
      const frame = () => {
        const t = (performance.now() - start) / 2000;
        if (arrived > seen) {
          changedFrames++;
          seen = arrived;
        }
        details.add(canvas.dataset.detail);
        if (t >= 1) {
          resolve();
          return;
        }
        api.setParameter(opId, { transform: { scale: [1.1 + 0.5 * t, 1] } }, { preview: true }).catch(() => {});
        requestAnimationFrame(frame);
      };
      requestAnimationFrame(frame);
    });
    const seconds = (performance.now() - start) / 1000;
    off();
    await api.setParameter(opId, { transform: { scale: [1.6, 1] } });
    const detailAfterRelease = canvas.dataset.detail;
    const statusAfterRelease = document.querySelector('[data-testid="status-solve"]').textContent;
    // After the first preview (which puts the rest pose back at the op's input).
    const steady = arrivals.length > 1 ? (arrivals.length - 1) / ((arrivals.at(-1) - arrivals[0]) / 1000) : 0;
    return { rate: changedFrames / seconds, changedFrames, seconds, firstMs: arrivals[0] - start, steady,
      final: api.document().ops[0].op.transform.scale, details: [...details], detailAfterRelease, statusAfterRelease,
      software: canvas.dataset.antialias === 'false' };
  });
  console.log(`slider: ${measured.changedFrames} frames with new positions in ${measured.seconds.toFixed(2)} s = `
    + `${measured.rate.toFixed(1)} updates/s (first after ${measured.firstMs.toFixed(0)} ms; then ${measured.steady.toFixed(1)}/s)`);
  expect(measured.final).toEqual([1.6, 1]);
  // On a CPU rasteriser (this headless Chromium) a 52k-triangle mesh is drawn
  // simplified while it moves, and in full as soon as the value is released.
  if (measured.software) expect(measured.details).toContain('proxy');
  expect(measured.detailAfterRelease).toBe('full');
  // The status bar reports the release's full solve, not the last preview's.
  // (At 20k vertices the full solve can end at the default cap of 50 and say so.)
  expect(measured.statusAfterRelease).toMatch(/^solve [0-9.]+ ms · [0-9]+ it( · cap reached)?$/);
  // The slider re-solves live: several distinct shapes arrive during the drag.
  // Its rate is measured and printed, not asserted (speed belongs to the
  // benchmarks; on the 2 shared cores of CI it swings 2x); issue 8 asks for 20/s
  // at 20k vertices: ANISO_SLIDER_MIN_RATE=20 makes this test check that.
  expect(measured.changedFrames).toBeGreaterThanOrEqual(2);
  test.info().annotations.push({ type: 'slider updates/s', description: measured.rate.toFixed(1) });
  if (process.env.ANISO_SLIDER_MIN_RATE) {
    expect(measured.rate).toBeGreaterThanOrEqual(Number(process.env.ANISO_SLIDER_MIN_RATE));
  }
  expect(pageErrors).toEqual([]);
});

// open() replays the ops one at a time ("Edit 2 of 3" in the progress) and
// keeps the states between them: undo after it shows a kept state, with no
// replay. A document whose second op fails after its first has solved is
// refused, and the solver is back on the work in the page: the next edit
// gives bitwise what it gave there before.
test('open keeps the states between the ops for undo; a document failing at its second op leaves the solver on the work kept', async ({ page }) => {
  const pageErrors = await openApp(page);
  const { afterTwo, document } = await editSpot(page);
  const posted = await recordWorkerRequests(page);
  const replays = async () => (await posted()).filter((kind) => kind === 'replay').length;
  const positions = () => evaluateBulk(page, () => Array.from(window.anisoform.positions()));

  await page.evaluate((json) => window.anisoform.open(json), document);
  expect(await replays()).toBe(3); // one per op
  const before = await replays();
  const undone = await armChange(page, 'document');
  expect(await page.evaluate(() => window.anisoform.undo())).toBe(true);
  await undone();
  expect(bitwise(await positions(), afterTwo)).toBe(true);
  expect(await replays()).toBe(before); // the state after two ops was kept

  // The same edit on the state in the page, before and after a failed open.
  const edit = { method: 'anarap', direction: { type: 'global', vector: [1, 0, 0] }, transform: { scale: [1.2, 1] } };
  const again = async () => evaluateBulk(page, async (op) => {
    const api = window.anisoform;
    await api.select({ box: { min: [-1, -1, -1], max: [0, 1, 1] } });
    await api.deform(op);
    const result = Array.from(api.positions());
    api.undo(); // the edit (its state is kept: shown at once)
    return result;
  }, edit);
  const edited = await again();
  await page.evaluate(() => new Promise((resolve) => setTimeout(resolve, 300)));
  const [first] = document.ops;
  const failing = { ...document, ops: [first, { ...first, id: 'thick', op: { ...first.op, transform: { thickness: 1.2 } } }] };
  const refused = await page.evaluate((json) => window.anisoform.open(json).then(() => 'opened', (error) => error.message), failing);
  expect(refused).toMatch(/document\.ops\[1\] \(id 'thick'\).*thickness/);
  expect(bitwise(await positions(), afterTwo)).toBe(true);
  expect(bitwise(await again(), edited)).toBe(true);
  expect(pageErrors).toEqual([]);
});

test('document() lists an edit once it is solved: not while its commit or a re-run solves, not after a cancel', async ({ page }) => {
  const pageErrors = await openApp(page);
  // Polls document() every few ms while `start()` runs; what it showed before the end, and after.
  const watch = (start) => page.evaluate(async (code) => {
    const api = window.anisoform;
    const seen = new Set();
    let done = false;
    const calls = {
      commit: () => api.deform({ method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: [1.3, 1] } }),
      rerun: () => api.setParameter(api.document().ops[0].id, { transform: { scale: [1.6, 1] } }),
    };
    const running = calls[code]().then(() => 'solved', (error) => error.code);
    running.finally(() => { done = true; });
    while (!done) {
      const { ops } = api.document();
      seen.add(JSON.stringify(ops.map((op) => op.op.transform.scale)));
      await new Promise((resolve) => setTimeout(resolve, 2));
    }
    return { outcome: await running, seen: [...seen], after: api.document().ops.map((op) => op.op.transform.scale) };
  }, start);
  await page.evaluate(() => window.anisoform.select({ box: { min: [-2, 0.3, -2], max: [2, 2, 2] } }, { falloff: 0.1 }));
  const commit = await watch('commit');
  expect(commit.outcome).toBe('solved');
  expect(commit.seen).toEqual(['[]']);
  expect(commit.after).toEqual([[1.3, 1]]);
  const rerun = await watch('rerun');
  expect(rerun.outcome).toBe('solved');
  expect(rerun.seen).toEqual(['[[1.3,1]]']);
  expect(rerun.after).toEqual([[1.6, 1]]);
  expect(pageErrors).toEqual([]);
});

test('a Thicken edit is listed and saved as Thicken', async ({ page }) => {
  const pageErrors = await openApp(page);
  await page.getByTestId('select-all').click();
  await page.locator('#direction-source').selectOption('global');
  await page.getByTestId('tool-thicken').click();
  await page.getByTestId('apply-thicken').click();
  await expect.poll(() => page.evaluate(() => window.anisoform.document().ops.length)).toBe(1);
  const [op] = await page.evaluate(() => window.anisoform.document().ops);
  expect(op.op.transform.scale[0]).toBe(1);
  expect(op.label).toBe('Thicken (AnARAP)');
  await expect(page.getByTestId(`op-select-${op.id}`)).toHaveText('Thicken (AnARAP)');
  expect(pageErrors).toEqual([]);
});

test("cancel() drops a setParameter preview left uncommitted, of the last op or an earlier one: the document's shape shows again", async ({ page }) => {
  const pageErrors = await openApp(page);
  const outcome = await evaluateBulk(page, async () => {
    const api = window.anisoform;
    const nextPositions = (live) => new Promise((resolve) => {
      const off = api.on('positions', (event) => {
        if (event.live !== live) return;
        off();
        resolve(Array.from(event.positions));
      });
    });
    await api.select({ box: { min: [-9, 0.5, -9], max: [9, 9, 9] } });
    await api.deform({ method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: [1.3, 1] } });
    await api.select({ box: { min: [-9, -9, -9], max: [9, 0, 9] } });
    await api.deform({ method: 'anarap', direction: { type: 'global', vector: [1, 0, 0] }, transform: { scale: [1.2, 1] } });
    const committed = Array.from(api.positions());
    const history = api.document().ops.map((entry) => JSON.stringify(entry.op));
    const differs = (a, b) => a.some((value, i) => value !== b[i]);
    const results = [];
    for (const entry of api.document().ops) {
      const previewed = nextPositions(true);
      api.setParameter(entry.id, { transform: { scale: [1.8, 1] } }, { preview: true });
      const shown = await previewed;
      const restored = nextPositions(false);
      const cancelled = api.cancel();
      const back = await restored;
      results.push({ previewDiffers: differs(shown, committed), cancelled, back: !differs(back, committed),
        positions: !differs(Array.from(api.positions()), committed) });
    }
    return { results, opsKept: JSON.stringify(api.document().ops.map((entry) => JSON.stringify(entry.op))) === JSON.stringify(history) };
  });
  const each = { previewDiffers: true, cancelled: true, back: true, positions: true };
  expect(outcome).toEqual({ results: [each, each], opsKept: true });
  expect(pageErrors).toEqual([]);
});

test('an op given a new region edits that region; a region that selects nothing is said', async ({ page }) => {
  // ARAP's handles and pins follow the op's region: they used to stay the old
  // region's, so the old part stayed lifted while the Edits list showed the new one.
  const pageErrors = await openApp(page);
  const { rest, a, b, radius } = await evaluateBulk(page, () => {
    const positions = Array.from(window.anisoform.positions());
    const vertex = (i) => positions.slice(3 * i, 3 * i + 3);
    let maxX = 0;
    let minX = 0;
    for (let i = 0; i < positions.length / 3; i++) {
      if (positions[3 * i] > positions[3 * maxX]) maxX = i;
      if (positions[3 * i] < positions[3 * minX]) minX = i;
    }
    return { rest: positions, a: vertex(maxX), b: vertex(minX), radius: 0.15 * (positions[3 * maxX] - positions[3 * minX]) };
  });
  const move = [0, 0.2, 0];
  await page.evaluate(async ({ a, radius, move }) => {
    await window.anisoform.select({ sphere: { center: a, radius } });
    await window.anisoform.deform({ method: 'arap', move });
  }, { a, radius, move });
  await page.evaluate(({ b, radius }) => window.anisoform.setRegion('op-1', [{ region: { sphere: { center: b, radius } } }]), { b, radius });
  const moved = await evaluateBulk(page, () => Array.from(window.anisoform.positions()));
  const near = (centre, i) => Math.hypot(...[0, 1, 2].map((k) => rest[3 * i + k] - centre[k])) < radius;
  let inA = 0;
  let inB = 0;
  for (let i = 0; i < rest.length / 3; i++) {
    const offset = [0, 1, 2].map((k) => moved[3 * i + k] - rest[3 * i + k]);
    if (near(a, i)) {
      inA++;
      expect(Math.hypot(...offset)).toBe(0); // pinned: not selected any more
    } else if (near(b, i)) {
      inB++;
      offset.forEach((value, k) => expect(value).toBeCloseTo(move[k], 6)); // a handle now (positions() is float32)
    }
  }
  expect(inA).toBeGreaterThan(10);
  expect(inB).toBeGreaterThan(10);

  await page.evaluate(() => window.anisoform.setRegion('op-1', [{ region: { sphere: { center: [10, 10, 10], radius: 0.1 } } }]));
  await expect(page.getByTestId('warning'))
    .toContainText(/Move \(ARAP\): its region 'region-\d+' holds no vertex: the mesh is left unchanged/);
  expect(await evaluateBulk(page, () => Array.from(window.anisoform.positions()))).toEqual(rest);
  expect(pageErrors).toEqual([]);
});

test("the Edits list words an op as its tool does: a Thicken's one amount, a method and direction left to the defaults, a region stored as weights", async ({ page }) => {
  const pageErrors = await openApp(page);
  const document = await page.evaluate(async () => {
    const api = window.anisoform;
    await api.select({ all: true });
    await api.deform({ method: 'andefgrad', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: [1, 1.3] } });
    const json = api.document();
    // Written by hand: no method, no direction (the core's defaults); a region of weights.
    json.regions.push({ name: 'weights', steps: [{ region: { vertices: [0, 1, 2], weights: [1, 0.5, 0.2] } }] });
    json.ops.push({ id: 'by-hand', label: 'By hand', enabled: true, region: 'weights', op: { transform: { scale: 1.2 } } });
    await api.open(json);
    return api.document();
  });
  const [thicken] = document.ops;
  await page.getByTestId(`op-select-${thicken.id}`).click();
  // One amount, "Across ×", as the Thicken tool: "Stretch along 1" beside it was typed into for "thicker".
  await expect(page.getByTestId(`op-amount-${thicken.id}-Stretch along`)).toHaveCount(0);
  await expect(page.getByLabel('Across ×').last()).toHaveValue('1.3');
  await page.getByTestId(`op-select-${thicken.id}`).click();

  await page.getByTestId('op-select-by-hand').click();
  await expect(page.getByTestId('op-method-by-hand')).toHaveValue('anarap');
  await expect(page.locator('.op-direction-note')).toHaveText("Direction: the mesh's longest axis (none given)");
  await expect(page.getByText('Extra soft border (units)')).toBeVisible();
  expect(pageErrors).toEqual([]);
});
