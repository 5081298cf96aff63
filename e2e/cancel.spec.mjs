// Cancel (the button beside the progress, Esc, api.cancel()) stops a long
// committed solve at once: its promise rejects with code 'cancelled', a
// notice (not an error) says so, the mesh, the document and the history are
// exactly as before, and the solver comes back with that state: the next
// edit, undo and a replay of the document all work as if nothing happened.
import { evaluateBulk, expect, LONG_EDIT, meshPath, openApp, recordWorkerRequests, test, uploadFile, verticalRange } from './support.mjs';

async function setUp(page) {
  const pageErrors = await openApp(page);
  const loaded = await uploadFile(page, meshPath('closed/armadillo.off'));
  expect(loaded.ok).toBe(true);
  await page.evaluate(async ({ low: lowY, height }) => {
    const api = window.anisoform;
    window.__height = height;
    window.__events = [];
    api.on('error', (event) => window.__events.push({ kind: 'error', ...event }));
    // One committed edit first, so that there is history to keep.
    await api.select({ box: { min: [-1e9, lowY + 0.6 * height, -1e9], max: [1e9, 1e9, 1e9] } }, { falloff: 0.05 * height });
    await api.deform({ method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: [1.2, 1] } });
  }, await verticalRange(page));
  return pageErrors;
}

// Starts LONG_EDIT, waits until it is solving, stops it with `stop` (run in
// the page), and reports what happened.
async function cancelLongEdit(page, stop) {
  return evaluateBulk(page, async ({ edit, stop }) => {
    const api = window.anisoform;
    const before = { positions: Array.from(api.positions()), document: JSON.stringify(api.document()) };
    const started = api.deform(edit).then(() => ({ outcome: 'finished' }), (error) => ({ outcome: 'rejected', code: error.code, message: error.message, at: performance.now() }));
    // What the status bar says while it solves: the stage and how far. A
    // background step may run first (the factorization of the last commit's
    // shape, one step shown without a percentage): wait for the edit's own,
    // after its start has replaced what the last call left there.
    await new Promise((resolve) => setTimeout(resolve, 300));
    const status = document.querySelector('[data-testid="progress"]');
    const deadline = performance.now() + 20_000;
    while (!/(Solving|Preparing the solver) \d+ %/.test(status.textContent) && performance.now() < deadline) {
      await new Promise((resolve) => setTimeout(resolve, 50));
    }
    const progress = status.textContent;
    const cancelledAt = performance.now();
    const accepted = stop === 'api' ? api.cancel() : null;
    if (stop === 'button') document.querySelector('[data-testid="cancel-solve"]').click();
    if (stop === 'escape') document.querySelector('[data-testid="viewport"]').dispatchEvent(new KeyboardEvent('keydown', { key: 'Escape', bubbles: true }));
    const ended = await started;
    const after = { positions: Array.from(api.positions()), document: JSON.stringify(api.document()) };
    return {
      accepted,
      progress,
      ended,
      msToReject: ended.at - cancelledAt,
      samePositions: after.positions.every((x, i) => Object.is(x, before.positions[i])),
      sameDocument: after.document === before.document,
      cancelHidden: document.querySelector('[data-testid="cancel-solve"]').hidden,
      notice: document.querySelector('[data-testid="notice"]').textContent,
      noticeShown: !document.querySelector('[data-testid="notice"]').hidden,
      errorShown: !document.querySelector('[data-testid="error"]').hidden,
      events: window.__events,
    };
  }, { edit: LONG_EDIT, stop });
}

function expectKept(result) {
  // The core's progress: the iterations done of the 2000 allowed, or how far the
  // energy change has fallen towards the tolerance (or the factorization).
  expect(result.progress).toMatch(/(Solving|Preparing the solver) \d+ %/);
  expect(result.ended.outcome).toBe('rejected');
  expect(result.ended.code).toBe('cancelled');
  // Not waiting for the solve (tens of seconds): the worker is ended at once.
  console.log(`cancel: the edit's promise rejected ${result.msToReject.toFixed(0)} ms after the cancel`);
  expect(result.msToReject).toBeLessThan(2000);
  expect(result.samePositions).toBe(true);
  expect(result.sameDocument).toBe(true);
  expect(result.cancelHidden).toBe(true);
  expect(result.noticeShown).toBe(true);
  expect(result.notice).toContain('Cancelled: the solve was stopped');
  expect(result.errorShown).toBe(false);
  expect(result.events).toEqual([]);
}

// One page for the three ways to cancel (each set-up loads the armadillo):
// api.cancel() and what works after it, then the button and Esc.
test('api.cancel(), the Cancel button and Esc stop a long commit at once; the next edit, undo and a replay then work', { tag: '@speed' }, async ({ page }) => {
  test.setTimeout(180_000);
  const pageErrors = await setUp(page);
  const result = await cancelLongEdit(page, 'api');
  expect(result.accepted).toBe(true);
  expectKept(result);

  const after = await page.evaluate(async () => {
    const api = window.anisoform;
    const kept = Array.from(api.positions());
    const idle = api.cancel(); // nothing to stop now
    // The solver holds the state on screen again: a new edit applies on it...
    await api.deform({ method: 'anarap', direction: { type: 'global', vector: [1, 0, 0] }, transform: { scale: [1.15, 1] } });
    const edited = Array.from(api.positions());
    // ...and the notice that the cancel kept the state goes with that state.
    const noticeAfterEdit = !window.document.querySelector('[data-testid="notice"]').hidden;
    let moved = 0;
    for (let i = 0; i < kept.length; i++) moved = Math.max(moved, Math.abs(edited[i] - kept[i]));
    // ...undo brings back exactly the state the cancel kept...
    const undone = api.undo();
    await new Promise((resolve) => setTimeout(resolve, 300));
    const back = Array.from(api.positions()).every((x, i) => Object.is(x, kept[i]));
    api.redo();
    await new Promise((resolve) => setTimeout(resolve, 300));
    // ...and the document replays on the restarted solver's mesh (same hash) bitwise.
    const document = api.document();
    const before = Array.from(api.positions());
    await api.open(document);
    const replayed = Array.from(api.positions()).every((x, i) => Object.is(x, before[i]));
    return { idle, moved, noticeAfterEdit, undone, back, replayed, ops: api.document().ops.length, height: window.__height, events: window.__events };
  });
  expect(after.idle).toBe(false);
  expect(after.moved).toBeGreaterThan(0.01 * after.height);
  expect(after.noticeAfterEdit).toBe(false);
  expect(after.undone).toBe(true);
  expect(after.back).toBe(true);
  expect(after.replayed).toBe(true);
  expect(after.ops).toBe(2);
  expect(after.events).toEqual([]);

  expectKept(await cancelLongEdit(page, 'button'));
  expectKept(await cancelLongEdit(page, 'escape'));
  expect(pageErrors).toEqual([]);
});

// A change in the Edits list re-runs the ops from the one changed; Esc stops
// that too. The states on screen are still cached (the re-run replaces them
// only once it has solved every op), so the restarted solver gets them back
// without replaying a single op, and the list shows the op as it was.
test('Esc stops the re-run an Edits-list toggle started; the states on screen come back without a replay', { tag: '@speed' }, async ({ page }) => {
  test.setTimeout(120_000);
  const pageErrors = await setUp(page);
  // A second op whose re-run lasts a few seconds (400 iterations, no early stop).
  await page.evaluate(() => window.anisoform.deform({ method: 'anarap', direction: { type: 'global', vector: [1, 0, 0] },
    transform: { shear: 0.2 }, maxIterations: 400, tolerance: 1e-15, acceleration: 'none' }));
  const posted = await recordWorkerRequests(page);
  const before = await page.evaluate(() => ({ positions: Array.from(window.anisoform.positions()),
    document: JSON.stringify(window.anisoform.document()), undo: document.querySelector('[data-testid="undo"]').title }));
  const toggle = page.getByTestId('op-toggle-op-1');
  await toggle.uncheck();
  // As soon as the re-run shows its progress, Esc (the focus is on the checkbox, as after a click).
  await page.waitForFunction(() => /(Solving|Preparing the solver) \d+ %/.test(document.querySelector('[data-testid="progress"]')?.textContent ?? ''),
    null, { polling: 20 });
  const postedBefore = (await posted()).length;
  const progress = await page.evaluate(() => document.querySelector('[data-testid="progress"]').textContent);
  // Undo waits for the solve, and says so (the focus is on a checkbox, which takes no keys).
  await expect(page.getByTestId('undo')).toBeDisabled();
  await page.keyboard.press('Control+z');
  await expect(page.getByTestId('notice')).toContainText('Undo waits until the solve has ended');
  await page.keyboard.press('Escape');
  // The re-run says which op it is at.
  expect(progress).toMatch(/^Edit [12] of 2: (Solving|Preparing the solver) \d+ %/);
  await expect(page.getByTestId('notice')).toContainText('Cancelled: the solve was stopped');
  await expect(toggle).toBeChecked();
  const after = await page.evaluate(() => ({ positions: Array.from(window.anisoform.positions()),
    document: JSON.stringify(window.anisoform.document()), undo: document.querySelector('[data-testid="undo"]').title,
    errorShown: !document.querySelector('[data-testid="error"]').hidden }));
  after.posted = await posted(postedBefore);
  expect(after.positions.every((x, i) => Object.is(x, before.positions[i]))).toBe(true);
  expect(after.document).toBe(before.document);
  expect(after.undo).toBe(before.undo); // the toggle is no step of the history
  expect(after.posted).toContain('setMesh'); // the new worker...
  expect(after.posted).not.toContain('replay'); // ...given the cached state, not a replay of the ops
  expect(after.errorShown).toBe(false);
  expect(pageErrors).toEqual([]);
});
