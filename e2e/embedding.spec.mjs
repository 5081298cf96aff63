// The anisoform package embedded in an ordinary page (examples/embedding.html):
// two modellers are independent, and dispose() leaves nothing running
// (workers, observers, listeners and animation frames counted from outside by
// resource-census.mjs).
import { spotSceneGlb } from './gltf-scene.mjs';
import { evaluateBulk, expect, meshPath, test } from './support.mjs';
import { installResourceCensus } from './resource-census.mjs';

const census = (page) => page.evaluate(() => window.__census());

async function openExample(page) {
  const pageErrors = [];
  page.on('pageerror', (error) => pageErrors.push(error.message));
  await page.addInitScript(installResourceCensus);
  await page.goto('examples/embedding.html');
  await page.evaluate(() => Promise.all(Object.values(window.anisoformExample.modellers).map((m) => m.api.ready)));
  return pageErrors;
}

/** Frames requested during `ms` milliseconds, after `action` (none: an idle page). */
async function framesDuring(page, ms, action = async () => {}) {
  const before = (await census(page)).frames;
  await action();
  await page.waitForTimeout(ms);
  return (await census(page)).frames - before;
}

/** A full-UI modeller of the spool in a new host (data-testid `testid`, `height` high), as window[name]. */
function addSpoolModeller(page, { testid, height, name }) {
  return page.evaluate(async (options) => {
    const host = Object.assign(document.createElement('div'), { style: `height: ${options.height}` });
    host.dataset.testid = options.testid;
    document.body.append(host);
    window[options.name] = window.anisoformExample.createModeller(host, { ui: 'full', mesh: '../spool.off' });
    await window[options.name].api.ready;
  }, { testid, height, name });
}

/** Gives the third modeller's host element a new height: a live modeller redraws its view. */
function resizeThirdHost(page, height) {
  return page.evaluate((value) => {
    document.querySelector('[data-testid="host-third"]').style.height = value;
  }, height);
}

test('two modellers on one page are independent', async ({ page }) => {
  const pageErrors = await openExample(page);
  expect(await census(page)).toMatchObject({ workers: 2 });

  const counts = await page.evaluate(() => {
    const { spool, spot } = window.anisoformExample.modellers;
    return [spool.api.info().vertices, spot.api.info().vertices];
  });
  expect(counts).toEqual([649, 2930]);

  // An edit of the spool leaves Spot's positions, selection and history alone.
  const outcome = await evaluateBulk(page, async () => {
    const { spool, spot } = window.anisoformExample.modellers;
    const spotBefore = Array.from(spot.api.positions());
    const spoolBefore = Array.from(spool.api.positions());
    await spool.api.select({ box: { min: [0, -1, -1], max: [1, 1, 1] } });
    await spool.api.deform({ method: 'anarap', direction: { type: 'global', vector: [1, 0, 0] }, transform: { scale: [1.5, 1] } });
    const spoolMoved = spool.api.positions().some((value, i) => value !== spoolBefore[i]);
    const spotSame = spot.api.positions().every((value, i) => value === spotBefore[i]);
    return { spoolMoved, spotSame, spotSelected: spot.api.selection().some((w) => w > 0), spotCanUndo: spot.api.undo() };
  });
  expect(outcome).toEqual({ spoolMoved: true, spotSame: true, spotSelected: false, spotCanUndo: false });

  // Keyboard shortcuts go to the modeller with focus: Ctrl+Z in Spot's view
  // leaves the spool's edit in place; in the spool's view it undoes it.
  const spoolEdited = await evaluateBulk(page, () => Array.from(window.anisoformExample.modellers.spool.api.positions()));
  await page.getByTestId('host-spot').getByTestId('viewport').focus();
  await page.keyboard.press('Control+z');
  expect(await evaluateBulk(page, () => Array.from(window.anisoformExample.modellers.spool.api.positions()))).toEqual(spoolEdited);
  await page.getByTestId('host-spool').getByTestId('viewport').focus();
  await page.keyboard.press('Control+z');
  expect(await evaluateBulk(page, () => Array.from(window.anisoformExample.modellers.spool.api.positions()))).not.toEqual(spoolEdited);
  // Nothing focused: the page's keys are the page's.
  await page.evaluate(() => document.activeElement?.blur());
  const spoolNow = await evaluateBulk(page, () => Array.from(window.anisoformExample.modellers.spool.api.positions()));
  await page.keyboard.press('Control+Shift+z');
  expect(await evaluateBulk(page, () => Array.from(window.anisoformExample.modellers.spool.api.positions()))).toEqual(spoolNow);

  // The spool's bare viewport has no stylesheet: its heat-map legend, with no
  // heat map shown, is hidden all the same (it showed as an empty box).
  const spoolLegend = page.getByTestId('host-spool').getByTestId('heatmap-legend');
  await expect(spoolLegend).toHaveCount(1);
  await expect(spoolLegend).toBeHidden();
  // Spot's panel lives inside its own container.
  await expect(page.getByTestId('host-spot').locator('.side-panel')).toBeVisible();
  await expect(page.getByTestId('host-spool').locator('.side-panel')).toHaveCount(0);
  expect(pageErrors).toEqual([]);
});

test('two modellers with the full UI: each label works its own modeller\'s control, no id is on the page twice', async ({ page }) => {
  const pageErrors = await openExample(page);
  await addSpoolModeller(page, { testid: 'host-second', height: '500px', name: 'second' });
  const duplicates = () => page.evaluate(() => {
    const ids = [...document.querySelectorAll('[id]')].map((element) => element.id);
    return ids.filter((id, i) => ids.indexOf(id) !== i);
  });
  expect(await duplicates()).toEqual([]);
  const spot = page.getByTestId('host-spot');
  const second = page.getByTestId('host-second');
  // Its labels name and work its own fields.
  await second.getByText('Wireframe', { exact: true }).click();
  await expect(second.getByRole('checkbox', { name: 'Wireframe' })).toBeChecked();
  await expect(spot.getByRole('checkbox', { name: 'Wireframe' })).not.toBeChecked();
  await expect(second.getByRole('textbox', { name: 'Iterations' })).toHaveCount(1);
  // Open… in the second modeller opens into the second modeller.
  const [chooser] = await Promise.all([page.waitForEvent('filechooser'), second.getByText('Open…', { exact: true }).click()]);
  const loaded = page.evaluate(() => new Promise((resolve) => {
    const off = window.second.api.on('change', ({ reason }) => reason === 'load' && (off(), resolve()));
  }));
  await chooser.setFiles(meshPath('open/hemisphere.obj'));
  await loaded;
  const counts = await page.evaluate(() => [window.anisoformExample.modellers.spot.api.info().vertices,
    window.second.api.info().vertices]);
  expect(counts).toEqual([2930, 2051]);
  // A modeller made after the first is disposed takes the plain ids again.
  await page.evaluate(() => window.anisoformExample.modellers.spot.dispose());
  await addSpoolModeller(page, { testid: 'host-third', height: '500px', name: 'third' });
  expect(await duplicates()).toEqual([]);
  await expect(page.getByTestId('host-third').locator('#display-wireframe')).toHaveCount(1);
  expect(pageErrors).toEqual([]);
});

test('api calls in the wrong order: refusals are reported, a second cancel() is false, a dispose stops a solve as cancelled', async ({ page }) => {
  const pageErrors = await openExample(page);
  const outcome = await evaluateBulk(page, async () => {
    const { createModeller } = window.anisoformExample;
    const host = Object.assign(document.createElement('div'), { style: 'height: 200px' });
    document.body.append(host);
    const empty = createModeller(host, { ui: 'none' });
    const errors = [];
    empty.api.on('error', (event) => errors.push(event.message));
    await empty.api.ready;
    const refusals = [];
    for (const call of [() => empty.api.select({ all: true }), () => empty.api.flatten({})]) {
      refusals.push(await call().then(() => 'resolved', (error) => error.code));
    }
    empty.dispose();

    const modeller = createModeller(host, { ui: 'none', mesh: '../spot_triangulated.obj' });
    await modeller.api.ready;
    await modeller.api.select({ all: true });
    const long = { method: 'anarap', tolerance: 0, maxIterations: 10000, direction: { type: 'global', vector: [0, 1, 0] },
      transform: { scale: [1.2, 1] } };
    const first = modeller.api.deform(long).then(() => 'resolved', (error) => error.code);
    await new Promise((resolve) => setTimeout(resolve, 50));
    const cancels = [modeller.api.cancel(), modeller.api.cancel()];
    const cancelled = await first;
    // Cancelled in the same task it was asked for: stopped before it reaches the worker.
    const before = Array.from(modeller.api.positions());
    const sameTask = modeller.api.deform(long).then(() => 'resolved', (error) => error.code);
    const cancelledAtOnce = modeller.api.cancel();
    const sameTaskOutcome = await sameTask;
    const unchanged = modeller.api.positions().every((value, i) => value === before[i]);
    const ops = modeller.api.document().ops.length;
    const second = modeller.api.deform(long).then(() => 'resolved', (error) => error.code);
    await new Promise((resolve) => setTimeout(resolve, 50));
    modeller.dispose();
    // Disposed in the same task as the edit asked for: stopped as well, not refused.
    const third = createModeller(host, { ui: 'none', mesh: '../spot_triangulated.obj' });
    await third.api.ready;
    const queued = third.api.deform(long).then(() => 'resolved', (error) => error.code);
    third.dispose();
    const afterDispose = await third.api.deform(long).then(() => 'resolved', (error) => `${error.code}: ${error.message}`);
    return { refusals, errors, cancels, cancelled, sameTask: { cancelledAtOnce, outcome: sameTaskOutcome, unchanged, ops },
      disposed: await second, disposedAtOnce: await queued, afterDispose };
  });
  expect(outcome.sameTask).toEqual({ cancelledAtOnce: true, outcome: 'cancelled', unchanged: true, ops: 0 });
  expect(outcome.disposedAtOnce).toBe('cancelled');
  expect(outcome.afterDispose).toBe('bad-parameter: deform(): this modeller was disposed');
  expect(outcome.refusals).toEqual(['bad-parameter', 'bad-parameter']);
  expect(outcome.errors).toHaveLength(2);
  expect(outcome.errors.every((message) => message.includes('no mesh is loaded yet'))).toBe(true);
  expect(outcome.cancels).toEqual([true, false]);
  expect(outcome.cancelled).toBe('cancelled');
  expect(outcome.disposed).toBe('cancelled');
  expect(pageErrors).toEqual([]);
});

test('dispose stops the worker, the frames, the observers and every listener', async ({ page }) => {
  const pageErrors = await openExample(page);
  const withBoth = await census(page);
  expect(withBoth.workers).toBe(2);

  // One disposed: the other still works.
  await page.getByRole('button', { name: 'Dispose' }).first().click();
  const withSpot = await census(page);
  expect(withSpot.workers).toBe(1);
  expect(withSpot.listeners).toBeLessThan(withBoth.listeners);
  expect(withSpot.observers).toBeLessThan(withBoth.observers);
  await expect(page.getByTestId('host-spool')).toBeEmpty();
  const spotStillWorks = await page.evaluate(async () => {
    const { spot } = window.anisoformExample.modellers;
    await spot.api.select({ sphere: { center: [0, 0, 0], radius: 0.3 } });
    return spot.api.selection().some((w) => w > 0);
  });
  expect(spotStillWorks).toBe(true);
  await page.getByRole('button', { name: 'Dispose' }).last().click();

  // None left: what the page held before any modeller is what it holds now,
  // and a new modeller's share goes with it again.
  const none = await census(page);
  expect(none).toMatchObject({ workers: 0, observers: 0 });
  expect(await framesDuring(page, 400)).toBe(0);
  const held = await page.evaluate(() => Object.values(window.anisoformExample.modellers).map((m) => m.held));
  expect(held).toEqual([0, 0]);

  await addSpoolModeller(page, { testid: 'host-third', height: '300px', name: 'third' });
  const withThird = await census(page);
  expect(withThird.workers).toBe(1);
  expect(withThird.listeners).toBeGreaterThan(none.listeners);
  expect(withThird.observers).toBeGreaterThan(0);
  // Frames are drawn on demand: none once idle (what the load scheduled, the
  // direction glyphs, may still draw first; a loop never stops), one when the
  // view changes.
  await expect.poll(() => framesDuring(page, 400), { timeout: 10_000 }).toBe(0);
  expect(await framesDuring(page, 300, () => resizeThirdHost(page, '320px'))).toBeGreaterThan(0);
  // The embedder's listeners are gone with it: calls made after dispose fire no events.
  await page.evaluate(() => {
    window.thirdEvents = [];
    for (const event of ['error', 'change', 'progress', 'document']) {
      window.third.api.on(event, (payload) => window.thirdEvents.push(`${event}: ${payload?.message ?? payload?.reason ?? ''}`));
    }
  });
  await page.evaluate(() => window.third.dispose());
  const afterDispose = await page.evaluate(async () => {
    const api = window.third.api;
    const deform = await api.deform({ transform: { scale: [1.2, 1] } }).then(() => 'resolved', (error) => error.message);
    return { deform, undo: api.undo(), redo: api.redo(), events: window.thirdEvents };
  });
  expect(afterDispose).toEqual({ deform: expect.stringMatching(/disposed/), undo: false, redo: false, events: [] });
  expect(afterDispose.deform).not.toContain('undefined');
  expect(await census(page)).toMatchObject({ workers: 0, observers: 0, listeners: none.listeners });
  expect(await page.evaluate(() => window.third.held)).toBe(0);
  await expect(page.getByTestId('host-third')).toBeEmpty();
  expect(await framesDuring(page, 400, () => resizeThirdHost(page, '280px'))).toBe(0);

  // A disposed modeller's api refuses with a clear message.
  const refusal = await page.evaluate(() => window.third.api.select({ all: true }).then(() => 'resolved', (error) => error.message));
  expect(refusal).toMatch(/disposed/);
  expect(pageErrors).toEqual([]);
});

test('<anisoform-modeller>: src loads, events come out as DOM events, .api works, a new ui keeps the worker, removal disposes, .solvers shares workers', async ({ page }) => {
  const pageErrors = await openExample(page);
  const workersBefore = (await census(page)).workers;

  const first = await page.evaluate(async () => {
    const element = document.createElement('anisoform-modeller');
    element.setAttribute('ui', 'none');
    element.setAttribute('src', '../spool.off');
    element.style.height = '240px';
    window.events = [];
    for (const type of ['change', 'error', 'progress']) {
      element.addEventListener(type, (event) => window.events.push({ type, isCustom: event instanceof CustomEvent, detail: event.detail }));
    }
    document.body.append(element);
    window.element = element;
    await element.api.ready;
    return { vertices: element.api.info().vertices, canvases: element.querySelectorAll('canvas').length };
  });
  expect(first).toEqual({ vertices: 649, canvases: 1 });
  expect((await census(page)).workers).toBe(workersBefore + 1);
  let events = await page.evaluate(() => window.events);
  expect(events.every((event) => event.isCustom)).toBe(true);
  expect(events.filter((e) => e.type === 'change').map((e) => e.detail)).toEqual([{ reason: 'load' }]);
  expect(events.some((e) => e.type === 'progress' && typeof e.detail.message === 'string')).toBe(true);

  // A new src loads; a missing one is an 'error' event and the mesh stays.
  const loaded = page.evaluate(() => new Promise((resolve) => {
    window.element.addEventListener('change', (event) => resolve(event.detail), { once: true });
  }));
  await page.evaluate(() => window.element.setAttribute('src', '../spot_triangulated.obj'));
  expect(await loaded).toEqual({ reason: 'load' });
  expect(await page.evaluate(() => window.element.api.info().vertices)).toBe(2930);

  const failed = page.evaluate(() => new Promise((resolve) => {
    window.element.addEventListener('error', (event) => resolve(event.detail), { once: true });
  }));
  await page.evaluate(() => window.element.setAttribute('src', '../no-such-part.glb'));
  const error = await failed;
  expect(error.message).toMatch(/no-such-part\.glb.*HTTP 404/);
  expect(await page.evaluate(() => window.element.api.info().vertices)).toBe(2930);

  // Edits through .api are the element's 'change' events.
  const edited = await page.evaluate(async () => {
    window.events = [];
    await window.element.api.select({ all: true });
    await window.element.api.deform({ method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: [1.2, 1] } });
    return window.events.filter((e) => e.type === 'change').map((e) => e.detail.reason);
  });
  expect(edited).toEqual(['selection', 'positions', 'document']); // a committed edit is a new op in the document

  // A new ui lays the same modeller out anew: the same solver worker, the
  // mesh loaded and its edits, bitwise, and no load heard again.
  const rebuilt = await evaluateBulk(page, async () => {
    const loaded = new Promise((resolve) => {
      window.element.addEventListener('change', resolve, { once: true });
    });
    window.element.setAttribute('src', '../spot_triangulated.obj');
    await loaded;
    const created = window.__census().workersCreated;
    const rest = Array.from(window.element.api.positions());
    await window.element.api.select({ box: { min: [-1, 0.5, -1], max: [1, 2, 2] } });
    await window.element.api.deform({ method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: [1.3, 1] } });
    const edited = Array.from(window.element.api.positions());
    const changes = [];
    const heard = (event) => changes.push(event.detail);
    window.element.addEventListener('change', heard);
    window.element.setAttribute('ui', 'full');
    await window.element.api.ready;
    await new Promise((resolve) => setTimeout(resolve, 100));
    window.element.removeEventListener('change', heard);
    const positions = window.element.api.positions();
    return {
      newWorkers: window.__census().workersCreated - created,
      panel: window.element.querySelectorAll('.side-panel').length,
      vertices: window.element.api.info().vertices,
      ops: window.element.api.document().ops.length,
      kept: positions.length === edited.length && edited.every((value, i) => Object.is(value, positions[i])),
      moved: edited.some((value, i) => value !== rest[i]),
      changes,
    };
  });
  expect(rebuilt).toEqual({ newWorkers: 0, panel: 1, vertices: 2930, ops: 1, kept: true, moved: true, changes: [] });

  // A ui not known: an 'error' event naming it, and the modeller kept with its work; a known one then rebuilds.
  const refusedUi = await page.evaluate(async () => {
    const api = window.element.api;
    const failed = new Promise((resolve) => {
      window.element.addEventListener('error', (event) => resolve(event.detail), { once: true });
    });
    window.element.setAttribute('ui', 'bogus');
    const error = await failed;
    const kept = window.element.api === api && window.element.querySelectorAll('.side-panel').length === 1;
    window.element.setAttribute('ui', 'none');
    await window.element.api.ready;
    return { error, kept, panel: window.element.querySelectorAll('.side-panel').length, ops: window.element.api.document().ops.length };
  });
  expect(refusedUi).toEqual({ error: { code: 'bad-parameter', message: "anisoform-modeller: ui must be 'full' or 'none', got 'bogus'" },
    kept: true, panel: 0, ops: 1 });

  // Two ui changes in quick succession go on from the work (the second
  // change came while the first rebuild was still opening it). An api taken
  // before them is still the element's: its calls and listeners go on.
  const quick = await evaluateBulk(page, async () => {
    const element = window.element;
    const { api } = element;
    let heard = 0;
    api.on('positions', () => heard++);
    const before = Array.from(api.positions());
    element.setAttribute('ui', 'full');
    element.setAttribute('ui', 'none');
    await api.ready;
    const after = api.positions();
    await api.select({ all: true });
    await api.deform({ method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: [1.1, 1] } });
    const ops = api.document().ops.length;
    await api.undo();
    return { sameApi: element.api === api, ops, same: after.every((value, i) => value === before[i]), heard: heard > 0 };
  });
  expect(quick).toEqual({ sameApi: true, ops: 2, same: true, heard: true });


  // Moved to another parent in one task: the same modeller, its work kept.
  const moved = await page.evaluate(async () => {
    const element = window.element;
    const { api } = element;
    const parent = document.body.appendChild(document.createElement('section'));
    parent.append(element);
    await new Promise((resolve) => setTimeout(resolve, 50));
    return { same: element.api === api, ops: api.document().ops.length, workers: window.__census().workers };
  });
  expect(moved).toEqual({ same: true, ops: 1, workers: workersBefore + 1 });

  // A src that failed (404), then a good one: ready resolves with it.
  const recovered = await page.evaluate(async () => {
    const element = window.element;
    element.setAttribute('src', '../nope.obj');
    const failed = await element.api.ready.then(() => 'resolved', (error) => error.message);
    element.setAttribute('src', '../spot_triangulated.obj');
    const ready = await element.api.ready.then(() => 'resolved', (error) => error.message);
    return { failed, ready, vertices: element.api.info().vertices };
  });
  expect(recovered.failed).toContain('404');
  expect(recovered).toMatchObject({ ready: 'resolved', vertices: 2930 });

  // Moved by code that awaits between removing and inserting it (an async
  // framework hook): the same modeller goes on (a microtask teardown had
  // disposed it, and it was built again from src, its edits gone).
  const movedAwaiting = await page.evaluate(async () => {
    const element = window.element;
    const { api } = element;
    const canvas = element.querySelector('canvas');
    const parent = element.parentElement;
    element.remove();
    await Promise.resolve();
    await Promise.resolve();
    parent.append(element);
    await new Promise((resolve) => setTimeout(resolve, 50));
    return { sameApi: element.api === api, sameCanvas: element.querySelector('canvas') === canvas };
  });
  expect(movedAwaiting).toEqual({ sameApi: true, sameCanvas: true });

  // Removed from the page: disposed (at the end of the task).
  const afterRemoval = await page.evaluate(async () => {
    window.element.remove();
    await new Promise((resolve) => setTimeout(resolve, 0));
    return { api: window.element.api, children: window.element.childElementCount };
  });
  expect(afterRemoval).toEqual({ api: null, children: 0 });
  expect((await census(page)).workers).toBe(workersBefore);

  // With .solvers, elements share a pool: a removed element's worker goes
  // to the next element instead of ending. Anything else is refused.
  const shared = await page.evaluate(async () => {
    const solvers = window.anisoformExample.createSolverPool();
    const make = async () => {
      const element = document.createElement('anisoform-modeller');
      element.setAttribute('ui', 'none');
      element.setAttribute('src', '../spool.off');
      element.style.height = '200px';
      element.solvers = solvers;
      document.body.append(element);
      await element.api.ready;
      await element.api.select({ all: true }); // the worker idle
      return element;
    };
    const created = window.__census().workersCreated;
    (await make()).remove();
    await new Promise((resolve) => setTimeout(resolve, 0)); // disposed a task after the one that removed it
    const kept = { kept: solvers.size, workers: window.__census().workers };
    const second = await make();
    const taken = { kept: solvers.size, newWorkers: window.__census().workersCreated - created, vertices: second.api.info().vertices };
    second.remove();
    await new Promise((resolve) => setTimeout(resolve, 0));
    solvers.dispose();
    let refusal = 'accepted';
    try {
      second.solvers = { keep: 1 };
    } catch (error) {
      refusal = `${error.code}: ${error.message}`;
    }
    return { kept, taken, workersAfter: window.__census().workers, refusal };
  });
  expect(shared.kept).toEqual({ kept: 1, workers: workersBefore + 1 });
  expect(shared.taken).toEqual({ kept: 0, newWorkers: 1, vertices: 649 });
  expect(shared.workersAfter).toBe(workersBefore);
  expect(shared.refusal).toBe('bad-parameter: anisoform-modeller: solvers must be a pool made by createSolverPool(), or null');
  expect(pageErrors).toEqual([]);
});

// A ui change while an edit solved rebuilt the modeller: the edit was
// rejected ("disposed"), and the load was replayed to the listeners.
test('<anisoform-modeller>: a ui change while an edit solves lays the same modeller out: the edit is applied, no load is heard again', async ({ page }) => {
  const pageErrors = await openExample(page);
  const outcome = await evaluateBulk(page, async () => {
    const element = document.createElement('anisoform-modeller');
    element.setAttribute('src', '../spot_triangulated.obj');
    element.style.height = '300px';
    document.body.append(element);
    await element.api.ready;
    const { api } = element;
    const created = window.__census().workersCreated;
    await api.select({ box: { min: [-1, 0.5, -1], max: [1, 2, 2] } });
    const rest = Array.from(api.positions());
    const heard = [];
    for (const type of ['change', 'error']) element.addEventListener(type, (event) => heard.push(`${type} ${event.detail.reason ?? event.detail.message}`));
    const apiHeard = [];
    for (const event of ['change', 'document', 'positions', 'error']) {
      api.on(event, (payload) => apiHeard.push(event === 'change' ? `change ${payload.reason}` : event));
    }
    const edit = api.deform({ method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: [1.3, 1] } })
      .then(() => 'applied', (error) => `rejected: ${error.message}`);
    element.setAttribute('ui', 'none');
    const panelsWhileSolving = element.querySelectorAll('.side-panel').length;
    const result = await edit;
    await api.ready;
    await new Promise((resolve) => setTimeout(resolve, 100));
    const edited = Array.from(api.positions());
    const none = {
      result, panelsWhileSolving, heard: [...heard], apiHeard: [...apiHeard],
      ops: api.document().ops.length,
      moved: edited.some((value, i) => value !== rest[i]),
      selected: api.selection().filter((weight) => weight > 0).length,
      canvases: element.querySelectorAll('canvas').length,
    };
    // Back to the full ui: its panels show the work as it is (the edit to undo), and work it.
    element.setAttribute('ui', 'full');
    await api.ready;
    const undo = element.querySelector('[data-testid=undo]');
    const full = { undoTitle: undo.title, edits: element.querySelectorAll('[data-testid=op-list] > li').length,
      selection: element.querySelector('.selection-count').textContent };
    undo.click();
    await new Promise((resolve) => setTimeout(resolve, 100));
    const undone = api.positions();
    // A control of the panel focused when the ui changes: the 3D view has
    // the focus after, there and back (it fell to the page's body).
    element.querySelector('[data-testid=tool-stretch]').focus();
    element.setAttribute('ui', 'none');
    const focusNone = document.activeElement === element.querySelector('canvas');
    element.setAttribute('ui', 'full');
    const focusFull = document.activeElement === element.querySelector('canvas');
    return { none, full, undone: undone.every((value, i) => value === rest[i]), newWorkers: window.__census().workersCreated - created,
      heardAfter: heard.slice(none.heard.length), focusNone, focusFull };
  });
  expect(outcome.focusNone).toBe(true);
  expect(outcome.focusFull).toBe(true);
  expect(outcome.none).toMatchObject({ result: 'applied', panelsWhileSolving: 0, heard: ['change positions', 'change document'], ops: 1, moved: true,
    canvases: 1 });
  expect(outcome.none.apiHeard).toEqual(['positions', 'change positions', 'document', 'change document']);
  expect(outcome.none.selected).toBeGreaterThan(0);
  expect(outcome.full.undoTitle).toMatch(/^Undo Stretch/);
  expect(outcome.full.edits).toBe(1);
  expect(outcome.full.selection).toMatch(/vertices selected$/);
  expect(outcome.undone).toBe(true);
  expect(outcome.newWorkers).toBe(0);
  expect(outcome.heardAfter).toEqual(['change positions', 'change document']);
  expect(pageErrors).toEqual([]);
});

test('workerUrl and wasmUrl say where the solver is loaded from', async ({ page }) => {
  const pageErrors = await openExample(page);
  const outcome = await page.evaluate(async () => {
    // Where the example's own modellers found them: the worker from the page,
    // the WASM named in the worker's code (relative to the worker).
    const worker = performance.getEntriesByType('resource').map((entry) => entry.name)
      .find((name) => /solver-worker[^/]*\.js$/.test(name));
    const wasmName = (await (await fetch(worker)).text()).match(/anisoform-[\w-]+\.wasm/)[0];
    const wasm = new URL(wasmName, worker).href;
    const attempt = async (options) => {
      const host = Object.assign(document.createElement('div'), { style: 'height: 200px' });
      document.body.append(host);
      const modeller = window.anisoformExample.createModeller(host, { ui: 'none', mesh: '../spool.off', ...options });
      try {
        await modeller.api.ready;
        return { vertices: modeller.api.info().vertices };
      } catch (error) {
        return { error: error.message };
      } finally {
        modeller.dispose();
        host.remove();
      }
    };
    return {
      moved: await attempt({ workerUrl: `${worker}?copy`, wasmUrl: `${wasm}?copy` }),
      missingWasm: await attempt({ wasmUrl: new URL('no-such.wasm', worker).href }),
      missingWorker: await attempt({ workerUrl: new URL('no-such-worker.js', worker).href }),
      notWasm: await attempt({ wasmUrl: `${worker}?as-wasm` }),
      otherOrigin: (() => {
        try {
          window.anisoformExample.createModeller(document.body, { ui: 'none', workerUrl: 'https://example.invalid/solver.js' });
          return 'created';
        } catch (error) {
          return { code: error.code, message: error.message, children: document.body.querySelectorAll('.anisoform-root, canvas').length };
        }
      })(),
      children: document.body.querySelectorAll('canvas').length,
    };
  });
  expect(outcome.moved).toEqual({ vertices: 649 });
  // Each failure names the URL and why it failed, not only the browser's "magic word" or "could not start".
  expect(outcome.missingWasm.error).toMatch(/cannot load the WASM module from .*no-such\.wasm: HTTP 404/);
  expect(outcome.notWasm.error).toMatch(/cannot load the WASM module from .*solver-worker[^ ]*\?as-wasm: it is not WebAssembly \(it begins "/);
  expect(outcome.missingWorker.error).toMatch(/The solver stopped: the worker could not start from .*no-such-worker\.js: HTTP 404/);
  expect(outcome.otherOrigin.code).toBe('bad-parameter');
  expect(outcome.otherOrigin.message).toMatch(/^the solver worker cannot start from https:\/\/example\.invalid\/solver\.js: /);
  expect(outcome.otherOrigin.children).toBe(outcome.children);
  expect(pageErrors).toEqual([]);
});

test('a solver pool hands a disposed modeller\'s idle worker to the next one, which solves as a new one does', async ({ page }) => {
  const pageErrors = await openExample(page);
  for (const button of await page.getByRole('button', { name: 'Dispose' }).all()) await button.click();
  expect((await census(page)).workers).toBe(0);

  const outcome = await evaluateBulk(page, async () => {
    const { createModeller, createSolverPool } = window.anisoformExample;
    const workers = () => window.__census().workers;
    const hosts = [];
    const open = async (options) => {
      const host = Object.assign(document.createElement('div'), { style: 'height: 200px' });
      document.body.append(host);
      hosts.push(host);
      const modeller = createModeller(host, { ui: 'none', mesh: '../spool.off', ...options });
      await modeller.api.ready;
      // The worker answers requests in order: once this selection is made,
      // the load's background factorization is over and the worker idle
      // (a worker disposed in the middle of one is ended, as in a solve).
      await modeller.api.select({ all: true });
      return modeller;
    };
    const stretch = async (modeller) => {
      await modeller.api.select({ box: { min: [-1, 0.2, -1], max: [1, 1, 1] } }, { falloff: 0.1 });
      const { iterations } = await modeller.api.deform({ method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: [1.3, 1] } });
      return { iterations, positions: Array.from(modeller.api.positions()) };
    };
    const solvers = createSolverPool();

    // The first modeller starts its own worker; disposed, the worker is kept.
    const first = await open({ solvers });
    const rest = Array.from(first.api.positions());
    const firstEdit = await stretch(first);
    first.dispose();
    const afterFirst = { kept: solvers.size, workers: workers(), held: first.held };

    // The second takes it: no new worker, a new session (the mesh as loaded), the same results.
    const second = await open({ solvers });
    const takenBy = { kept: solvers.size, workers: workers(), rest: Array.from(second.api.positions()).every((value, i) => value === rest[i]) };
    const secondEdit = await stretch(second);

    // A worker with a request in flight is ended, not kept: here a solve of
    // many iterations, disposed once it reports progress.
    const solving = new Promise((resolve) => {
      const off = second.api.on('progress', () => {
        off();
        resolve();
      });
    });
    const running = second.api.deform({ method: 'anarap', direction: { type: 'global', vector: [1, 0, 0] }, transform: { scale: [1.5, 1] }, maxIterations: 10000, tolerance: 0 });
    await solving;
    second.dispose();
    const busy = { kept: solvers.size, workers: workers(), running: await running.then(() => 'resolved', (error) => error.message) };

    // Another worker or WASM location is another kind of worker: not handed over.
    const third = await open({ solvers });
    third.dispose();
    const worker = performance.getEntriesByType('resource').map((entry) => entry.name).find((name) => /solver-worker[^/]*\.js$/.test(name));
    const moved = await open({ solvers, workerUrl: `${worker}?copy` });
    const otherKind = { kept: solvers.size, workers: workers() };
    moved.dispose();

    // keep: 1 keeps the last one given back; dispose() ends the idle ones and any given back later.
    const full = { kept: solvers.size, workers: workers() };
    solvers.dispose();
    const disposed = { kept: solvers.size, workers: workers() };
    const late = await open({ solvers });
    late.dispose();
    const afterLate = { kept: solvers.size, workers: workers() };

    // An idle worker is ended after idleSeconds (a very long wait is long,
    // not a timer that fires at once).
    const brief = createSolverPool({ idleSeconds: 0.2 });
    const long = createSolverPool({ idleSeconds: 1e9 });
    (await open({ solvers: long })).dispose();
    (await open({ solvers: brief })).dispose();
    const briefKept = brief.size;
    await new Promise((resolve) => setTimeout(resolve, 600));
    const briefAfter = { kept: brief.size, longKept: long.size, workers: workers() };
    long.dispose();
    const workersAtEnd = workers();

    const refusals = [
      () => createSolverPool({ keep: -1 }),
      () => createSolverPool({ idleSeconds: 'long' }),
      () => createSolverPool({ size: 2 }),
      () => createModeller(hosts[0], { solvers: {} }),
    ].map((attempt) => {
      try {
        attempt();
        return 'accepted';
      } catch (error) {
        return `${error.code}: ${error.message}`;
      }
    });
    for (const host of hosts) host.remove();
    return { firstEdit, afterFirst, takenBy, secondEdit, busy, otherKind, full, disposed, afterLate, briefKept, briefAfter, workersAtEnd, refusals };
  });

  expect(outcome.afterFirst).toEqual({ kept: 1, workers: 1, held: 0 });
  expect(outcome.takenBy).toEqual({ kept: 0, workers: 1, rest: true });
  expect(outcome.firstEdit.iterations).toBeGreaterThan(0);
  expect(outcome.secondEdit).toEqual(outcome.firstEdit);
  expect(outcome.busy).toEqual({ kept: 0, workers: 0, running: 'stopped: this modeller was disposed' });
  expect(outcome.otherKind).toEqual({ kept: 1, workers: 2 });
  expect(outcome.full).toEqual({ kept: 1, workers: 1 });
  expect(outcome.disposed).toEqual({ kept: 0, workers: 0 });
  expect(outcome.afterLate).toEqual({ kept: 0, workers: 0 });
  expect(outcome.briefKept).toBe(1);
  expect(outcome.briefAfter).toEqual({ kept: 0, longKept: 1, workers: 1 });
  expect(outcome.workersAtEnd).toBe(0);
  expect(outcome.refusals).toEqual([
    'bad-parameter: createSolverPool: keep must be a whole number of workers, 0 or more, got -1',
    'bad-parameter: createSolverPool: idleSeconds must be a finite number of seconds, 0 or more, got "long"',
    "bad-parameter: createSolverPool: unknown option 'size' (options: keep, idleSeconds)",
    'bad-parameter: createModeller: solvers must be a pool made by createSolverPool()',
  ]);
  expect(pageErrors).toEqual([]);
});

test('a solver pool also hands on the 3D view: the next modeller draws on the same canvas and GL context, with nothing of the last one left in it', async ({ page }) => {
  const pageErrors = await openExample(page);
  for (const button of await page.getByRole('button', { name: 'Dispose' }).all()) await button.click();
  expect(await census(page)).toMatchObject({ contexts: 0, glObjects: 0 });
  const glb = (await spotSceneGlb(meshPath('closed/spot_triangulated.obj'))).toString('base64');

  const outcome = await page.evaluate(async (base64) => {
    const { createModeller, createSolverPool } = window.anisoformExample;
    const gl = () => {
      const { contexts, glObjects } = window.__census();
      return { contexts, glObjects };
    };
    const open = async (options) => {
      const host = Object.assign(document.createElement('div'), { style: 'height: 200px' });
      document.body.append(host);
      const modeller = createModeller(host, { ui: 'none', mesh: '../spool.off', ...options });
      await modeller.api.ready;
      await modeller.api.select({ all: true });
      // Two frames: the selection drawn.
      await new Promise((resolve) => requestAnimationFrame(() => requestAnimationFrame(resolve)));
      return { modeller, canvas: host.querySelector('canvas') };
    };
    const lost = (canvas) => canvas.getContext('webgl2').isContextLost();
    const solvers = createSolverPool();

    const first = await open({ solvers });
    const drawing = gl();
    first.modeller.dispose();
    const kept = { ...gl(), inDocument: first.canvas.isConnected, lost: lost(first.canvas) };

    const second = await open({ solvers });
    const handedOn = { ...gl(), sameCanvas: second.canvas === first.canvas };
    second.modeller.dispose();

    // A glTF drawn with its own materials and textures, then switched back to
    // the editing surface (its scene out of the view's), goes too: twice, the
    // context keeps the same (the renderer's own objects for materials it
    // has drawn stay, and do not grow).
    const gltfRound = async () => {
      const bytes = Uint8Array.from(atob(base64), (c) => c.charCodeAt(0));
      const { modeller, canvas } = await open({ solvers, mesh: bytes, meshName: 'spot-scene.glb', materials: true });
      const drawn = gl().glObjects;
      modeller.setMaterials(false);
      modeller.dispose();
      return { drawn, after: { ...gl(), sameCanvas: canvas === first.canvas } };
    };
    const gltfRounds = [await gltfRound(), await gltfRound()];

    // A kept context the browser takes while it waits is not handed on.
    const taken = first.canvas.getContext('webgl2');
    const takenEvent = new Promise((resolve) => first.canvas.addEventListener('webglcontextlost', resolve, { once: true }));
    taken.getExtension('WEBGL_lose_context').loseContext();
    await takenEvent;
    const afterTaken = await open({ solvers });
    const notHandedOn = { ...gl(), newCanvas: afterTaken.canvas !== first.canvas };
    afterTaken.modeller.dispose();
    solvers.dispose();
    const ended = { ...gl(), lost: lost(afterTaken.canvas) };

    // Without a pool, dispose gives the context back at once, as before.
    const alone = await open({});
    const aloneDrawing = { ...gl(), newCanvas: alone.canvas !== first.canvas };
    alone.modeller.dispose();
    return { drawing, kept, handedOn, gltfRounds, notHandedOn, ended, aloneDrawing, aloneEnded: { ...gl(), lost: lost(alone.canvas) } };
  }, glb);
  expect(outcome.drawing.contexts).toBe(1);
  expect(outcome.drawing.glObjects).toBeGreaterThan(0);
  // Kept out of the document with its context; what the modeller drew is freed.
  expect(outcome.kept).toMatchObject({ contexts: 1, inDocument: false, lost: false });
  expect(outcome.kept.glObjects).toBeLessThan(outcome.drawing.glObjects);
  // The next modeller draws the same mesh on it: no second context, the same GL objects.
  expect(outcome.handedOn).toEqual({ ...outcome.drawing, sameCanvas: true });
  const [gltfFirst, gltfSecond] = outcome.gltfRounds;
  expect(gltfFirst.drawn).toBeGreaterThan(gltfFirst.after.glObjects);
  expect(gltfFirst.after).toMatchObject({ contexts: 1, sameCanvas: true });
  expect(gltfSecond).toEqual(gltfFirst);
  expect(outcome.notHandedOn).toEqual({ ...outcome.drawing, newCanvas: true });
  expect(outcome.ended).toEqual({ contexts: 0, glObjects: 0, lost: true });
  expect(outcome.aloneDrawing).toEqual({ ...outcome.drawing, newCanvas: true });
  expect(outcome.aloneEnded).toEqual({ contexts: 0, glObjects: 0, lost: true });
  expect(pageErrors).toEqual([]);
});

test('<anisoform-modeller edits>: saved edits open with src, alone on the mesh loaded, or with a new src; bad ones are refused and the work kept', async ({ page }) => {
  const pageErrors = await openExample(page);
  // Two saved edits of the spool (one op, two ops), made by a modeller of the page, served as files.
  const made = await evaluateBulk(page, async () => {
    const host = document.createElement('div');
    host.style.height = '200px';
    document.body.append(host);
    const modeller = window.anisoformExample.createModeller(host, { ui: 'none', mesh: '../spool.off' });
    const { api } = modeller;
    await api.ready;
    await api.select({ box: { min: [-1, 0.2, -1], max: [1, 1, 1] } });
    await api.deform({ method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: [1.3, 1] } });
    const one = { document: api.document(), positions: Array.from(api.positions()) };
    await api.select({ sphere: { center: [0, 0, 0], radius: 0.4 } });
    await api.deform({ method: 'andefgrad', direction: { type: 'global', vector: [1, 0, 0] }, transform: { shear: 0.2 } });
    const two = { document: api.document(), positions: Array.from(api.positions()) };
    modeller.dispose();
    host.remove();
    return { one, two };
  });
  // Served with the server's own headers (its strict CSP), as a file beside the example would be.
  const serve = (name, body) => page.route(`**/${name}`, async (route) => {
    const response = await route.fetch({ url: new URL('../spool.off', route.request().url()).href });
    await route.fulfill({ response, body, contentType: 'application/json' });
  });
  await serve('spool-one.json', JSON.stringify(made.one.document));
  await serve('spool-two.json', JSON.stringify(made.two.document));
  await serve('broken.json', '{"format": ');

  const state = () => evaluateBulk(page, () => ({ vertices: window.element.api.info().vertices,
    ops: window.element.api.document().ops.length, positions: Array.from(window.element.api.positions()) }));
  const nextError = () => page.evaluate(() => new Promise((resolve) => {
    window.element.addEventListener('error', (event) => resolve(event.detail.message), { once: true });
  }));
  const bitwise = (a, b) => a.length === b.length && a.every((value, i) => Object.is(value, b[i]));

  // src and edits at the start: the edits replayed on the mesh, bitwise.
  await page.evaluate(async () => {
    const element = document.createElement('anisoform-modeller');
    element.setAttribute('ui', 'none');
    element.setAttribute('src', '../spool.off');
    element.setAttribute('edits', '../spool-one.json');
    element.style.height = '240px';
    window.loads = 0;
    element.addEventListener('change', (event) => { if (event.detail.reason === 'load') window.loads++; });
    document.body.append(element);
    window.element = element;
    await element.api.ready;
  });
  let now = await state();
  expect([now.vertices, now.ops]).toEqual([649, 1]);
  expect(bitwise(now.positions, made.one.positions)).toBe(true);

  // edits alone: opened on the mesh loaded.
  await page.evaluate(() => window.element.setAttribute('edits', '../spool-two.json'));
  await expect.poll(async () => (await state()).ops).toBe(2);
  expect(bitwise((await state()).positions, made.two.positions)).toBe(true);

  // Not JSON: refused, naming why; the spool and its two ops stay.
  let failed = nextError();
  await page.evaluate(() => window.element.setAttribute('edits', '../broken.json'));
  expect(await failed).toMatch(/broken\.json is not JSON/);
  now = await state();
  expect([now.vertices, now.ops]).toEqual([649, 2]);
  expect(bitwise(now.positions, made.two.positions)).toBe(true);
  // A new src with edits of another mesh: refused, naming why, and the new
  // src shown without them (as the element's src says), not the spool.
  failed = nextError();
  await page.evaluate(() => {
    window.element.setAttribute('src', '../spot_triangulated.obj');
    window.element.setAttribute('edits', '../spool-one.json');
  });
  // The refusal names the mesh the edits were made on, as they name it.
  expect(await failed).toMatch(/\('spool\.off', 649 vertices, \d+ triangles\) does not match the mesh of spot_triangulated\.obj/);
  await expect.poll(async () => (await state()).vertices).toBe(2930);
  expect((await state()).ops).toBe(0);

  // src and edits changed together: one load, of the new mesh with the new edits.
  const loadsBefore = await page.evaluate(() => window.loads);
  await page.evaluate(() => {
    window.element.setAttribute('src', '../spool.off?again');
    window.element.setAttribute('edits', '../spool-one.json');
  });
  await expect.poll(async () => (await state()).ops).toBe(1);
  expect(bitwise((await state()).positions, made.one.positions)).toBe(true);
  expect(await page.evaluate(() => window.loads)).toBe(loadsBefore + 1);

  // A src that is not there, with edits: fetched once, one error, about the
  // mesh (it was fetched twice, and the first error blamed the edits).
  const fetches = [];
  page.on('request', (request) => request.url().includes('missing-mesh.obj') && fetches.push(request.url()));
  await page.evaluate(() => {
    window.errors = [];
    window.element.addEventListener('error', (event) => window.errors.push(event.detail.message));
    window.element.setAttribute('src', '../missing-mesh.obj');
  });
  await expect.poll(() => page.evaluate(() => window.errors.length)).toBe(1);
  await page.waitForTimeout(500);
  const errors = await page.evaluate(() => window.errors);
  expect(errors).toHaveLength(1);
  expect(errors[0]).toMatch(/^Could not load the mesh: .*missing-mesh\.obj/);
  expect(fetches).toHaveLength(1);
  expect((await state()).ops).toBe(1);
  await page.evaluate(() => window.element.remove());
  expect(pageErrors).toEqual([]);
});

test('<anisoform-modeller edits> that cannot be opened: the mesh is shown without them, the error reported, and edits apply as on the mesh alone', async ({ page }) => {
  const pageErrors = await openExample(page);
  const edit = { method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: [1.3, 1] } };
  // Saved edits of the spool whose second op fails once the first has solved.
  const failing = await page.evaluate(async (op) => {
    const host = document.createElement('div');
    host.style.height = '200px';
    document.body.append(host);
    const modeller = window.anisoformExample.createModeller(host, { ui: 'none', mesh: '../spool.off' });
    await modeller.api.ready;
    await modeller.api.select({ box: { min: [-1, 0.2, -1], max: [1, 1, 1] } });
    await modeller.api.deform(op);
    const json = modeller.api.document();
    modeller.dispose();
    host.remove();
    const [first] = json.ops;
    return { ...json, ops: [first, { ...first, id: 'thick', op: { ...first.op, transform: { thickness: 1.2 } } }] };
  }, edit);
  await page.route('**/failing-edits.json', async (route) => {
    const response = await route.fetch({ url: new URL('../spool.off', route.request().url()).href });
    await route.fulfill({ response, body: JSON.stringify(failing), contentType: 'application/json' });
  });

  const outcomes = await evaluateBulk(page, async (op) => {
    const make = (edits) => {
      const element = document.createElement('anisoform-modeller');
      element.setAttribute('ui', 'none');
      element.setAttribute('src', '../spool.off');
      if (edits) element.setAttribute('edits', edits);
      element.style.height = '160px';
      const errors = [];
      element.addEventListener('error', (event) => errors.push(event.detail.message));
      document.body.append(element);
      return { element, errors };
    };
    const results = {};
    for (const [name, edits] of [['plain', null], ['missing', '../missing-edits.json'], ['failing', '../failing-edits.json']]) {
      const { element, errors } = make(edits);
      await element.api.ready;
      const { api } = element;
      const shown = { vertices: api.info().vertices, ops: api.document().ops.length };
      // A band the first op of the failing edits would have moved: selected on the solver's rest pose.
      const band = await api.select({ box: { min: [-1, 0.3, -1], max: [1, 0.4, 1] } });
      await api.select({ box: { min: [-1, 0.2, -1], max: [1, 1, 1] } });
      await api.deform(op);
      results[name] = { shown, band, errors, positions: Array.from(api.positions()) };
      element.remove();
    }
    return results;
  }, edit);
  const bitwise = (a, b) => a.length === b.length && a.every((value, i) => Object.is(value, b[i]));
  expect(outcomes.plain.errors).toEqual([]);
  for (const name of ['missing', 'failing']) {
    expect(outcomes[name].shown).toEqual({ vertices: 649, ops: 0 });
    expect(outcomes[name].band).toBe(outcomes.plain.band);
    expect(bitwise(outcomes[name].positions, outcomes.plain.positions)).toBe(true);
  }
  expect(outcomes.missing.errors).toEqual([expect.stringMatching(/edits were not opened.*missing-edits\.json could not be fetched \(HTTP 404\)/)]);
  expect(outcomes.failing.errors).toEqual([expect.stringMatching(/document\.ops\[1\] \(id 'thick'\).*thickness/)]);
  expect(pageErrors).toEqual([]);
});

test('materials (option, setMaterials, the element\'s attribute) draws a glTF mesh with its own materials', async ({ page }) => {
  const pageErrors = await openExample(page);
  const glb = (await spotSceneGlb(meshPath('closed/spot_triangulated.obj'))).toString('base64');
  const outcome = await page.evaluate(async (base64) => {
    const bytes = Uint8Array.from(atob(base64), (c) => c.charCodeAt(0));
    const { createModeller } = window.anisoformExample;
    const surfaceOf = (root) => root.querySelector('[data-testid=viewport]').dataset.surface;
    const host = Object.assign(document.createElement('div'), { style: 'height: 200px' });
    document.body.append(host);
    let refused = 'accepted';
    try {
      createModeller(host, { materials: 'yes' });
    } catch (error) {
      refused = `${error.code}: ${error.message}`;
    }
    const modeller = createModeller(host, { ui: 'none', mesh: new Uint8Array(bytes), meshName: 'spot-scene.glb', materials: true });
    await modeller.api.ready;
    const option = surfaceOf(host);
    modeller.setMaterials(false);
    const off = surfaceOf(host);
    modeller.dispose();
    host.remove();

    const element = document.createElement('anisoform-modeller');
    element.setAttribute('ui', 'none');
    element.setAttribute('materials', '');
    element.style.height = '200px';
    document.body.append(element);
    await element.api.ready;
    await element.api.load(new Uint8Array(bytes), 'spot-scene.glb');
    const attribute = surfaceOf(element);
    element.removeAttribute('materials');
    const removed = surfaceOf(element);
    element.remove();
    return { refused, option, off, attribute, removed };
  }, glb);
  expect(outcome).toEqual({
    refused: 'bad-parameter: createModeller: materials must be true or false, got "yes"',
    option: 'materials',
    off: 'editing',
    attribute: 'materials',
    removed: 'editing',
  });
  expect(pageErrors).toEqual([]);
});

test("an event's positions and document are the listener's own: changing them changes nothing of the modeller's", async ({ page }) => {
  const pageErrors = await openExample(page);
  const outcome = await page.evaluate(async () => {
    const host = document.createElement('div');
    host.style.height = '200px';
    document.body.append(host);
    const modeller = window.anisoformExample.createModeller(host, { ui: 'none', mesh: '../spool.off' });
    const { api } = modeller;
    await api.ready;
    const seen = {};
    api.on('positions', (event) => {
      seen.positions = event.positions;
      event.positions.fill(0);
    });
    api.on('document', (json) => {
      seen.document = json;
      json.ops.length = 0;
    });
    await api.select({ box: { min: [-1, 0.2, -1], max: [1, 1, 1] } });
    await api.deform({ method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: [1.3, 1] } });
    const positions = api.positions();
    const exported = new TextDecoder().decode(await api.export('obj'));
    const firstVertex = exported.split('\n').find((line) => line.startsWith('v ')).split(/\s+/).slice(1).map(Number);
    const result = {
      listenerZeroed: seen.positions.every((value) => value === 0),
      positionsKept: positions.some((value) => value !== 0),
      firstVertexAgrees: firstVertex.every((value, k) => Math.abs(value - positions[k]) < 1e-5),
      listenerDocumentEmptied: seen.document.ops.length === 0,
      opsKept: api.document().ops.length,
      undo: api.undo(),
    };
    modeller.dispose();
    host.remove();
    return result;
  });
  expect(outcome).toEqual({ listenerZeroed: true, positionsKept: true, firstVertexAgrees: true, listenerDocumentEmptied: true,
    opsKept: 1, undo: true });
  expect(pageErrors).toEqual([]);
});

test('a mesh that is neither a URL nor bytes is refused by its type, not for a missing file name', async ({ page }) => {
  const pageErrors = await openExample(page);
  const refusals = await page.evaluate(async () => {
    const host = Object.assign(document.createElement('div'), { style: 'height: 200px' });
    document.body.append(host);
    const modeller = window.anisoformExample.createModeller(host, { ui: 'none', mesh: 42 });
    const messages = [await modeller.api.ready.then(() => 'ready', (error) => `${error.code}: ${error.message}`)];
    for (const source of [null, [1, 2, 3], { name: 'part.obj' }]) {
      messages.push(await modeller.load(source, 'part.obj').then(() => 'loaded', (error) => `${error.code}: ${error.message}`));
    }
    modeller.dispose();
    host.remove();
    return messages;
  });
  const expected = (what) => `load() takes a File, Blob, ArrayBuffer or typed array (or, in a modeller, a URL); got ${what}.`;
  expect(refusals[0]).toBe(`bad-parameter: Could not load the file: ${expected('a number')}`);
  expect(refusals.slice(1)).toEqual(['null', 'an array', 'an object'].map((what) =>
    `bad-parameter: Could not load part.obj: ${expected(what)}`));
  expect(pageErrors).toEqual([]);
});

test("a load asked for while the starting mesh downloads is the mesh shown; a load replaced by a later one is 'cancelled'", async ({ page }) => {
  // The starting mesh, downloaded last, replaced the page's own load while
  // both promises said the page's mesh was in (from an embedder's session).
  const pageErrors = await openExample(page);
  const outcome = await page.evaluate(async () => {
    const { createModeller } = window.anisoformExample;
    const host = Object.assign(document.createElement('div'), { style: 'height: 200px' });
    document.body.append(host);
    const modeller = createModeller(host, { ui: 'none', mesh: '../spool.off' });
    const loaded = await modeller.load('../spot_triangulated.obj');
    await modeller.api.ready;
    await new Promise((resolve) => setTimeout(resolve, 300));
    const afterStart = modeller.api.info().vertices;
    // Two loads in a row: the first is replaced, the second shown.
    const first = modeller.load('../spool.off').then((result) => result.vertices, (error) => error.code);
    const second = await modeller.load('../spot_triangulated.obj');
    const result = { loaded: loaded.vertices, afterStart, first: await first, second: second.vertices, shown: modeller.api.info().vertices };
    modeller.dispose();
    return result;
  });
  expect(outcome).toEqual({ loaded: 2930, afterStart: 2930, first: 'cancelled', second: 2930, shown: 2930 });
  expect(pageErrors).toEqual([]);
});

test("the package's styles keep to the modeller, and the element can be registered under a name of the page's", async ({ page }) => {
  // style.css styled the host page's own .button, .row, .field and .message
  // (a Bootstrap .row became a flex row); defineModellerElement('my-modeller')
  // always threw, the class being registered already (from an embedder's session).
  const pageErrors = await openExample(page);
  const outcome = await page.evaluate(async () => {
    const host = document.createElement('div');
    host.innerHTML = '<div class="row">a</div><p class="message">b</p><button class="button">c</button>';
    document.body.append(host);
    const [row, message, button] = host.children;
    const inApp = document.querySelector('.app .row');
    const styles = {
      row: getComputedStyle(row).display,
      message: getComputedStyle(message).display,
      buttonPadding: getComputedStyle(button).padding,
      appRow: getComputedStyle(inApp).display,
    };
    window.anisoformExample.defineModellerElement('my-modeller');
    const element = document.createElement('my-modeller');
    element.setAttribute('ui', 'none');
    element.style.height = '200px';
    element.setAttribute('src', '../spool.off');
    document.body.append(element);
    await element.api.ready;
    return { styles, vertices: element.api.info().vertices, same: customElements.get('anisoform-modeller') !== customElements.get('my-modeller') };
  });
  expect(outcome.styles.row).toBe('block');
  expect(outcome.styles.message).toBe('block');
  expect(outcome.styles.buttonPadding).not.toBe('5px 11px');
  expect(outcome.styles.appRow).toBe('flex');
  expect(outcome.vertices).toBe(649);
  expect(outcome.same).toBe(true);
  expect(pageErrors).toEqual([]);
});

test('the full UI in a narrow column of a wide page is laid out as on a phone: the view over a sheet of at most half the height', async ({ page }) => {
  // The narrow layout followed the window (@media): a 400 px column on a
  // 1280 px screen kept the 280 px panel beside a 20 px view.
  await page.setViewportSize({ width: 1280, height: 900 });
  const pageErrors = await openExample(page);
  const boxes = await page.evaluate(async () => {
    const layoutIn = async (width) => {
      const host = Object.assign(document.createElement('div'), { style: `width: ${width}px; height: 640px` });
      document.body.append(host);
      const modeller = window.anisoformExample.createModeller(host, { ui: 'full', mesh: '../spool.off' });
      await modeller.api.ready;
      const box = (selector) => host.querySelector(selector).getBoundingClientRect().toJSON();
      const result = { host: box('.app'), view: box('.viewport'), panel: box('.side-panel'),
        toggle: getComputedStyle(host.querySelector('.sheet-toggle')).display };
      modeller.dispose();
      host.remove();
      return result;
    };
    return { narrow: await layoutIn(400), wide: await layoutIn(1000) };
  });
  const { narrow, wide } = boxes;
  expect(narrow.view.width).toBeCloseTo(narrow.host.width, 0);
  expect(narrow.panel.top).toBeGreaterThanOrEqual(narrow.view.bottom - 1);
  expect(narrow.panel.height).toBeLessThanOrEqual(narrow.host.height / 2 + 1);
  expect(narrow.view.height).toBeGreaterThan(narrow.host.height / 3);
  expect(narrow.toggle).not.toBe('none');
  // A wide column keeps the panel beside the view.
  expect(wide.panel.right).toBeLessThanOrEqual(wide.view.left + 1);
  expect(wide.view.width).toBeGreaterThan(600);
  expect(wide.toggle).toBe('none');
  expect(pageErrors).toEqual([]);
});

test('edits called without awaiting take the selection of their call; an edit still queued when a new mesh loads is not applied, and says so without an error', async ({ page }) => {
  // deform, deform, select(B) without awaiting solved the second edit on B
  // (the selection was read when the edit ran); deform then load refused the
  // edit as "saved edits replay only on the mesh they were made on", an error.
  const pageErrors = await openExample(page);
  const outcome = await page.evaluate(async () => {
    const api = window.anisoformExample.modellers.spot.api;
    const errors = [];
    const notices = [];
    api.on('error', ({ message }) => errors.push(message));
    const A = { sphere: { center: [0, 0.3, 0.5], radius: 0.4 } };
    const B = { sphere: { center: [0, -0.6, 0], radius: 0.3 } };
    const op = { method: 'andefgrad', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: [1.2, 1] } };
    await api.select(A);
    await Promise.all([api.deform(op), api.deform(op), api.select(B)]);
    const document = api.document();
    const stepsOf = (opIndex) => document.regions.find((r) => r.name === document.ops[opIndex].region).steps;
    const regions = [stepsOf(0), stepsOf(1)];
    const selectedAfter = api.info().selected ?? null;

    const bytes = await (await fetch('../spool.off')).arrayBuffer();
    const queued = api.deform(op).then(() => 'applied', (error) => `${error.code}: ${error.message}`);
    const loaded = await api.load(bytes, 'spool.off');
    return { regions, selectedAfter, queued: await queued, loaded: loaded.vertices, ops: api.document().ops.length, errors, notices };
  });
  expect(outcome.regions[0]).toEqual([{ region: { sphere: { center: [0, 0.3, 0.5], radius: 0.4 } } }]);
  expect(outcome.regions[1]).toEqual(outcome.regions[0]);
  expect(outcome.queued).toBe('cancelled: A new mesh was loaded before this edit ran: it was not applied.');
  expect(outcome.loaded).toBe(649);
  expect(outcome.ops).toBe(0);
  expect(outcome.errors).toEqual([]);
  expect(pageErrors).toEqual([]);
});

test('the package imports outside a browser (a server render): no HTMLElement is needed until a modeller is made', async () => {
  // `class ... extends HTMLElement` and its registration ran at import:
  // "ReferenceError: HTMLElement is not defined" in Node.
  const imported = await import('../web/dist-lib/anisoform.js');
  expect(Object.keys(imported).sort()).toEqual(['AnisoformModellerElement', 'createModeller', 'createSolverPool', 'defineModellerElement']);
  expect(() => imported.defineModellerElement()).not.toThrow();
});

test('a lost WebGL context is said as an error, the restored one as a notice, and the view is drawn again', async ({ page }) => {
  // Beyond about 16 live contexts a page, the browser takes the oldest: the
  // view stayed blank without a word, and after a restore it was black.
  const pageErrors = await openExample(page);
  const outcome = await page.evaluate(async () => {
    const { api } = window.anisoformExample.modellers.spot;
    const canvas = document.querySelector('[data-testid="host-spot"] [data-testid="viewport"]');
    const events = [];
    api.on('error', ({ code, message }) => events.push(`${code}: ${message}`));
    const lose = canvas.getContext('webgl2').getExtension('WEBGL_lose_context');
    const lost = new Promise((resolve) => canvas.addEventListener('webglcontextlost', resolve, { once: true }));
    lose.loseContext();
    await lost;
    await new Promise((resolve) => setTimeout(resolve, 100)); // a restore asked for within the loss's own task is not made
    const restored = new Promise((resolve) => canvas.addEventListener('webglcontextrestored', resolve, { once: true }));
    lose.restoreContext();
    await restored;
    return { events };
  });
  expect(outcome.events).toHaveLength(1);
  expect(outcome.events[0]).toMatch(/^display: The 3D view lost its WebGL context/);
  const spot = page.getByTestId('host-spot');
  await expect(spot.getByTestId('notice')).toContainText('The 3D view has its WebGL context again.');
  // It still draws and edits: a select works and a frame is drawn.
  expect(await framesDuring(page, 300, () => page.evaluate(() => window.anisoformExample.modellers.spot.api.select({ all: true })))).toBeGreaterThan(0);
  expect(pageErrors).toEqual([]);
});

test('a second modeller in a container that holds one is refused until the first is disposed', async ({ page }) => {
  const pageErrors = await openExample(page);
  const outcome = await page.evaluate(async () => {
    const { createModeller } = window.anisoformExample;
    const host = Object.assign(document.createElement('div'), { style: 'height: 300px' });
    document.body.append(host);
    const first = createModeller(host, { ui: 'none', mesh: '../spool.off' });
    await first.api.ready;
    let refusal = 'accepted';
    try {
      createModeller(host, { ui: 'none' });
    } catch (error) {
      refusal = `${error.code}: ${error.message}`;
    }
    first.dispose();
    const second = createModeller(host, { ui: 'none', mesh: '../spool.off' });
    await second.api.ready;
    const views = host.querySelectorAll('canvas').length;
    second.dispose();
    return { refusal, views };
  });
  expect(outcome.refusal).toBe('bad-parameter: createModeller: this container holds a modeller already: dispose() it first, or give each modeller its own container');
  expect(outcome.views).toBe(1);
  expect(pageErrors).toEqual([]);
});
