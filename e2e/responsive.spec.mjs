// The page stays responsive with a big mesh: loading the 200k-vertex koala
// (its picking BVH and normals are built in the worker, its GPU buffers go up
// over a few frames when they are big), and a committed AnARAP edit that runs
// in the worker while the page keeps answering evaluate round trips and keeps
// its animation frames coming.
//
// What is asserted: no main-thread task of 200 ms or more from the upload to
// the frame that shows the mesh, nor while the solver works (a frozen page
// would show one), and 95 % of round trips under 200 ms. And a select right
// after the load is answered while the worker still prepares the solver
// (Session.prepareStep, a part at a time), not after all of it: it waited
// 3.2 s here for the whole preparation and the moving mesh's simplification.
// The longest gap between animation frames is printed, not asserted: on 2
// cores SwiftShader's compositor shares them with the solver, and gaps of
// 1.1 s and 2.9 s were seen with no long task on the page and round trips
// under 100 ms (the page answering; the software GPU starved).
import { canvasCentre, expect, meshPath, openApp, test, uploadFile } from './support.mjs';

const LIMIT_MS = 200;

// One page, as a user works: the koala is loaded (the load's long tasks and a
// pick), then edited (the solve's round trips and long tasks).
test('the 200k-vertex koala loads with no main-thread task of 200 ms or more, can be picked at once, and the page answers within 200 ms while it solves', { tag: '@speed' }, async ({ page }) => {
  test.setTimeout(240_000);
  const pageErrors = await openApp(page);
  await page.evaluate(() => {
    const watch = { longTasks: [], done: false };
    new PerformanceObserver((list) => {
      if (!watch.done) watch.longTasks.push(...list.getEntries().map((entry) => Math.round(entry.duration)));
    }).observe({ type: 'longtask' });
    window.__watch = watch;
    // The load's background preparation ends with 'Ready' after the load's change.
    window.__prepared = { loaded: false, done: false };
    window.anisoform.on('change', ({ reason }) => {
      if (reason === 'load') window.__prepared.loaded = true;
    });
    window.anisoform.on('progress', ({ stage, message }) => {
      if (window.__prepared.loaded && stage === 'done' && message === 'Ready') window.__prepared.done = true;
    });
  });
  const outcome = await uploadFile(page, meshPath('large/koala_loop1_200k.ply'));
  expect(outcome).toMatchObject({ ok: true, info: { vertices: 199990, triangles: 399976 } });
  // The upper third of the koala (to be stretched upwards below), selected at once.
  const selected = await page.evaluate(async () => {
    const positions = window.anisoform.positions();
    let low = Infinity;
    let high = -Infinity;
    for (let i = 1; i < positions.length; i += 3) {
      low = Math.min(low, positions[i]);
      high = Math.max(high, positions[i]);
    }
    const cut = high - (high - low) / 3;
    const started = performance.now();
    const count = await window.anisoform.select({ box: { min: [-1e9, cut, -1e9], max: [1e9, 1e9, 1e9] } });
    return { count, ms: performance.now() - started, preparedBefore: window.__prepared.done };
  });
  console.log(`200k select right after the load: ${selected.ms.toFixed(0)} ms (${selected.count} vertices)`);
  expect(selected.count).toBeGreaterThan(1000);
  expect(selected.preparedBefore).toBe(false);
  // Until the mesh is drawn (a few frames after the load), and the long-task
  // entries of those frames are delivered.
  const picked = await page.evaluate(async (centre) => {
    for (let frame = 0; frame < 5; frame++) await new Promise((resolve) => requestAnimationFrame(resolve));
    await new Promise((resolve) => setTimeout(resolve, 200));
    window.__watch.done = true;
    return window.anisoform.pick(centre);
  }, (await canvasCentre(page)).canvas);
  const { longTasks: loadTasks } = await page.evaluate(() => window.__watch);
  console.log(`200k load: long tasks [${loadTasks.join(', ')}] ms (longest ${Math.max(0, ...loadTasks)})`);
  expect(Math.max(0, ...loadTasks)).toBeLessThan(LIMIT_MS);
  // The koala fills the centre of the framed view: the worker's BVH picks it.
  expect(picked).not.toBeNull();
  expect(picked.triangle).toBeGreaterThanOrEqual(0);
  expect(picked.triangle).toBeLessThan(399976);
  expect(picked.vertex).toBeGreaterThanOrEqual(0);
  expect(picked.vertex).toBeLessThan(199990);

  // Let the page draw the new mesh and selection before measuring.
  await expect
    .poll(async () => {
      const started = Date.now();
      await page.evaluate(() => new Promise((resolve) => requestAnimationFrame(() => resolve())));
      return Date.now() - started;
    }, { timeout: 60_000, intervals: [250] })
    .toBeLessThan(50);

  await page.evaluate(() => {
    const solve = { done: false, maxFrameGap: 0, result: null, longTasks: [] };
    // Main-thread tasks over 50 ms while the worker solves (there should be none).
    const observer = new PerformanceObserver((list) => {
      if (!solve.done) solve.longTasks.push(...list.getEntries().map((entry) => Math.round(entry.duration)));
    });
    observer.observe({ type: 'longtask' });
    window.__solve = solve;
    // 'change' fires in the task that applies the result: the watch stops
    // there, before the new positions are drawn.
    const off = window.anisoform.on('change', ({ reason }) => {
      if (reason === 'positions') {
        solve.done = true;
        off();
      }
    });
    let last = null;
    const watchFrames = (now) => {
      if (solve.done) return;
      if (last !== null) solve.maxFrameGap = Math.max(solve.maxFrameGap, now - last);
      last = now;
      requestAnimationFrame(watchFrames);
    };
    requestAnimationFrame(watchFrames);
    window.anisoform
      .deform({
        method: 'anarap',
        direction: { type: 'global', vector: [0, 1, 0] },
        transform: { scale: [1.3, 1] },
        maxIterations: 30,
        tolerance: 1e-12,
      })
      .then((result) => (solve.result = result));
  });

  const roundTrips = [];
  for (;;) {
    const started = Date.now();
    const done = await page.evaluate(() => window.__solve.done);
    if (done) break;
    roundTrips.push(Date.now() - started);
    await page.waitForTimeout(50);
  }
  await page.waitForFunction(() => window.__solve.result !== null);
  const { maxFrameGap, result, longTasks } = await page.evaluate(() => window.__solve);
  console.log(
    `200k solve: ${result.iterations} iterations, ${result.ms.toFixed(0)} ms in the worker; ` +
      `${roundTrips.length} round trips meanwhile (max ${Math.max(...roundTrips)} ms), ` +
      `longest gap between animation frames ${maxFrameGap.toFixed(0)} ms, long tasks [${longTasks.join(', ')}]`,
  );
  expect(roundTrips.length).toBeGreaterThan(5);
  expect(Math.max(0, ...longTasks)).toBeLessThan(LIMIT_MS);
  const sorted = [...roundTrips].sort((a, b) => a - b);
  expect(sorted[Math.floor(0.95 * (sorted.length - 1))]).toBeLessThan(LIMIT_MS);
  expect(pageErrors).toEqual([]);
});
