// After a committed edit, the solver factorizes the new shape in the
// background (announced as progress, ending in 'Ready'), so that the next
// edit does not pay for it in its first preview; the page is not busy
// meanwhile, and the next edit runs after the part in progress (the
// preparation goes a part at a time) and applies as usual.
import { expect, meshPath, openApp, test, uploadFile, verticalRange } from './support.mjs';

test('a commit starts the next factorization in the background, and the next edit still applies', { tag: '@speed' }, async ({ page }) => {
  test.setTimeout(120_000);
  const pageErrors = await openApp(page);
  // The load's own preparation (factorizing the new mesh) ends with 'done'
  // and 'Ready' after the load's change (the load's own 'done' has no
  // message); listening from before the upload, so that a quick one is not
  // missed (waiting for it afterwards cost the full
  // fallback of 20 s whenever it had ended already).
  await page.evaluate(() => {
    window.__loadPrepared = new Promise((resolve) => {
      let loaded = false;
      const offChange = window.anisoform.on('change', ({ reason }) => {
        if (reason === 'load') loaded = true;
      });
      const offProgress = window.anisoform.on('progress', ({ stage, message }) => {
        if (!loaded || stage !== 'done' || message !== 'Ready') return;
        offChange();
        offProgress();
        resolve();
      });
      setTimeout(resolve, 20_000);
    });
  });
  const loaded = await uploadFile(page, meshPath('closed/armadillo.off'));
  expect(loaded.ok).toBe(true);
  const result = await page.evaluate(async ({ low: lowY, height }) => {
    const api = window.anisoform;
    await window.__loadPrepared;
    const progress = [];
    api.on('progress', ({ stage, message }) => progress.push({ stage, message }));
    await api.select({ box: { min: [-1e9, lowY + 0.7 * height, -1e9], max: [1e9, 1e9, 1e9] } }, { falloff: 0.05 * height });
    const first = await api.deform({ method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: [1.3, 1] } });
    const afterFirst = progress.length;
    // The background factorization announces itself and ends in 'Ready'.
    await new Promise((resolve, reject) => {
      const check = () => progress.slice(afterFirst).some(({ stage, message }) => stage === 'done' && message === 'Ready');
      if (check()) return resolve();
      const off = api.on('progress', () => check() && (off(), resolve()));
      setTimeout(() => reject(new Error(`no 'done' after the commit: ${JSON.stringify(progress)}`)), 60_000);
    });
    const shapeAfterFirst = Array.from(api.positions());
    await api.select({ box: { min: [-1e9, -1e9, -1e9], max: [1e9, lowY + 0.3 * height, 1e9] } }, { falloff: 0.05 * height });
    const second = await api.deform({ method: 'anarap', direction: { type: 'global', vector: [1, 0, 0] }, transform: { scale: [1.2, 1] } });
    const shapeAfterSecond = Array.from(api.positions());
    let moved = 0;
    for (let i = 0; i < shapeAfterFirst.length; i++) moved = Math.max(moved, Math.abs(shapeAfterSecond[i] - shapeAfterFirst[i]));
    return { first, second, afterCommit: progress.slice(afterFirst), moved, height, ops: api.document().ops.length };
  }, await verticalRange(page));
  expect(result.first.iterations).toBeGreaterThan(0);
  const stages = result.afterCommit.map(({ stage }) => stage);
  expect(stages[0]).toBe('factorize');
  expect(stages).toContain('done');
  expect(result.second.iterations).toBeGreaterThan(0);
  expect(result.moved).toBeGreaterThan(0.01 * result.height);
  expect(result.ops).toBe(2);
  expect(pageErrors).toEqual([]);
});
