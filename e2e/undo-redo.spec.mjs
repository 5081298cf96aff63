// Undo and redo restore positions exactly (bitwise), by API and by keyboard.
import { evaluateBulk, expect, openApp, test } from './support.mjs';

test('undo and redo restore positions bitwise', async ({ page }) => {
  await openApp(page);
  const outcome = await page.evaluate(async () => {
    const api = window.anisoform;
    const same = (a, b) => a.length === b.length && a.every((value, i) => Object.is(value, b[i]));
    const original = api.positions();
    await api.select({ sphere: { center: [0, 0.3, 0.5], radius: 0.4 } }, { falloff: 0.2 });
    await api.deform({ method: 'anarap', direction: { type: 'global', vector: [0, 0, 1] }, transform: { scale: [1.4, 1] } });
    const stretched = api.positions();
    await api.deform({ method: 'andefgrad', direction: { type: 'global', vector: [1, 0, 0] }, transform: { shear: 0.3 } });
    const sheared = api.positions();
    const steps = [];
    steps.push(!same(original, stretched), !same(stretched, sheared));
    steps.push(api.undo() && same(api.positions(), stretched));
    steps.push(api.undo() && same(api.positions(), original));
    steps.push(api.redo() && same(api.positions(), stretched));
    steps.push(api.redo() && same(api.positions(), sheared));
    return steps;
  });
  expect(outcome).toEqual([true, true, true, true, true, true]);

  // Keyboard: Ctrl+Z twice (shear, stretch), then Ctrl+Shift+Z once.
  const snapshot = () => evaluateBulk(page, () => Array.from(window.anisoform.positions()));
  const sheared = await snapshot();
  await page.getByTestId('viewport').focus();
  await page.keyboard.press('Control+z');
  await page.keyboard.press('Control+z');
  await page.keyboard.press('Control+z'); // the selection step
  const undone = await snapshot();
  await page.keyboard.press('Control+Shift+z');
  await page.keyboard.press('Control+Shift+z');
  await page.keyboard.press('Control+Shift+z');
  const redone = await snapshot();
  expect(redone).toEqual(sheared);
  expect(undone).not.toEqual(sheared);

  // And the solver follows: an edit after undo starts from the restored mesh.
  const consistent = await page.evaluate(async () => {
    const api = window.anisoform;
    api.undo();
    api.undo();
    const restored = api.positions();
    await api.deform({ method: 'linear', direction: { type: 'global', vector: [1, 0, 0] }, transform: { scale: [1, 1] } });
    const after = api.positions();
    let worst = 0;
    for (let i = 0; i < after.length; i++) worst = Math.max(worst, Math.abs(after[i] - restored[i]));
    return worst;
  });
  expect(consistent).toBeLessThan(1e-5);
});
