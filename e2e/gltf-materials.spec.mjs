// Display > File's materials: a mesh opened from glTF drawn with its own
// materials and texture, in the edited shape (live and committed), in place
// of the editing surface; off again, the editing surface is back. Meshes of
// other formats have no materials of their own: the editing surface stays.
import { writeFileSync } from 'node:fs';

import { spotSceneGlb, withBaseColorTexture } from './gltf-scene.mjs';
import { countPixels, expect, meshPath, openApp, test, uploadFile } from './support.mjs';

// A 2x2 PNG, all one orange-red: the material's colour shows through it.
const redPng = (page) => page.evaluate(() => {
  const canvas = Object.assign(document.createElement('canvas'), { width: 2, height: 2 });
  const context = canvas.getContext('2d');
  context.fillStyle = 'rgb(255, 96, 64)';
  context.fillRect(0, 0, 2, 2);
  return canvas.toDataURL('image/png');
}).then((url) => Buffer.from(url.slice(url.indexOf(',') + 1), 'base64'));

// Canvas pixels that are clearly red: the material (0xcc8844 times the
// texture) is, the editing surface (a light neutral) and background are not.
const redPixels = async (page) => (await countPixels(page, 'viewport', { red: true })).lit;

test("File's materials draws a glTF mesh with its material and texture, in the edited shape", async ({ page }, testInfo) => {
  const pageErrors = await openApp(page);
  const canvas = page.getByTestId('viewport');
  const glb = withBaseColorTexture(await spotSceneGlb(meshPath('closed/spot_triangulated.obj')), await redPng(page));
  const file = testInfo.outputPath('spot-scene.glb');
  writeFileSync(file, glb);
  expect((await uploadFile(page, file)).ok).toBe(true);
  await page.evaluate(() => window.anisoform.frame());
  await expect(canvas).toHaveAttribute('data-surface', 'editing');
  await expect.poll(() => redPixels(page)).toBeLessThan(300); // the axis gizmo's x arrow is red

  const materials = page.getByLabel("File's materials (glTF)");
  await page.locator('#display-heatMap').selectOption('stretch');
  await expect(page.getByTestId('heatmap-legend')).toBeVisible();
  await materials.check();
  await expect(canvas).toHaveAttribute('data-surface', 'materials');
  // The heat map is the editing surface's: not drawn over the file's look, nor its legend.
  await expect(page.getByTestId('heatmap-legend')).toBeHidden();
  await page.locator('#display-heatMap').selectOption('off');
  await expect.poll(() => redPixels(page)).toBeGreaterThan(2000);
  const before = await redPixels(page);

  // A stretch of everything along y: the drawn product grows with it.
  await page.evaluate(async () => {
    await window.anisoform.select({ all: true });
    await window.anisoform.deform({ method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: [1.5, 1] } });
  });
  await expect.poll(() => redPixels(page)).toBeGreaterThan(1.15 * before);
  // Undo: the file's look follows the shape back.
  await page.getByTestId('undo').click();
  await expect.poll(async () => Math.abs((await redPixels(page)) - before)).toBeLessThan(0.03 * before);

  // The editing surface again (its selection tint, orange, cleared first).
  await page.getByRole('button', { name: 'Clear', exact: true }).click();
  await materials.uncheck();
  await expect(canvas).toHaveAttribute('data-surface', 'editing');
  await expect.poll(() => redPixels(page)).toBeLessThan(300); // the axis gizmo's x arrow is red

  // An OBJ has no materials of its own: the setting stays, the editing surface is drawn.
  await materials.check();
  expect((await uploadFile(page, meshPath('closed/spot_triangulated.obj'))).ok).toBe(true);
  await expect(canvas).toHaveAttribute('data-surface', 'editing');
  await expect(materials).toBeChecked();
  expect(pageErrors).toEqual([]);
});
