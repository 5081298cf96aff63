// The page opens with the default mesh drawn and ready to edit.
import { expect, litPixelCount, openApp, test } from './support.mjs';

test('the default mesh is drawn and ready to edit', async ({ page }) => {
  const pageErrors = await openApp(page, { navigate: true });
  const info = await page.evaluate(() => window.anisoform.info());
  expect(info).toEqual({ vertices: 2930, triangles: 5856, components: 1, boundaryLoops: 0, unitGuess: { name: 'm', mmPerUnit: 1000 } });

  const { lit, total } = await litPixelCount(page);
  expect(lit / total).toBeGreaterThan(0.05);

  // Milestones after navigation start: WASM solver ready, default mesh
  // loaded (read, checked, picking structure built), first frame drawn.
  const marks = await page.evaluate(() =>
    ['solver-ready', 'mesh-loaded', 'interactive'].map(
      (name) => performance.getEntriesByName(`anisoform:${name}`)[0]?.startTime ?? null,
    ),
  );
  expect(marks).not.toContain(null);
  const [solverReady, meshLoaded, interactive] = marks.map((ms) => ms.toFixed(0));
  test.info().annotations.push({ type: 'first interactive frame (ms)', description: interactive });
  console.log(`solver ready ${solverReady} ms, mesh loaded ${meshLoaded} ms, first interactive frame ${interactive} ms`);

  await expect(page.getByTestId('error')).toBeHidden();
  expect(pageErrors).toEqual([]);
});

// An embedder can tell a settled edit from one cut off by its iteration cap.
test('deform resolves whether its solve converged before the iteration cap', async ({ page }) => {
  const pageErrors = await openApp(page);
  const [capped, settled] = await page.evaluate(async () => {
    const api = window.anisoform;
    await api.select({ box: { min: [-1e9, 0, -1e9], max: [1e9, 1e9, 1e9] } });
    const op = { method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: [1.3, 1] } };
    const cut = await api.deform({ ...op, maxIterations: 2 });
    const cutStatus = document.querySelector('[data-testid="status-solve"]').textContent;
    await api.undo();
    return [{ ...cut, status: cutStatus }, await api.deform(op)];
  });
  expect(capped).toMatchObject({ iterations: 2, converged: false });
  // The user is told too, where the solve's figures are.
  expect(capped.status).toMatch(/^solve [\d.]+ ms · 2 it · cap reached$/);
  await expect(page.getByTestId('status-solve')).not.toContainText('cap');
  expect(settled.converged).toBe(true);
  expect(settled.iterations).toBeLessThan(50);
  expect(pageErrors).toEqual([]);
});
