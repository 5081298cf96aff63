// Issue 9 item 6: a pattern's physical size. The core guesses the mesh's unit
// from its size (metres for the SMPL torso panel), the Flatten panel says so
// and shows the pattern's size, and the exported SVG has that size, with its
// note in 4 mm type whatever the scale.
import { readFileSync } from 'node:fs';
import { expect, meshPath, openApp, saveScreenshot, test, uploadFile } from './support.mjs';

const TORSO = 'open/human_woman_torso_front_patch.obj';

// {width, height, viewBox, outlineBox: [w, h], fontSize, noteLines} of an exported SVG.
function readSvg(text) {
  const number = (pattern) => Number(text.match(pattern)[1]);
  const points = [...text.matchAll(/class="outline" d="([^"]+)"/g)]
    .flatMap(([, d]) => [...d.matchAll(/(-?[\d.]+) (-?[\d.]+)/g)].map(([, x, y]) => [Number(x), Number(y)]));
  const xs = points.map(([x]) => x), ys = points.map(([, y]) => y);
  return {
    width: number(/<svg[^>]* width="([\d.]+)mm"/),
    height: number(/<svg[^>]* height="([\d.]+)mm"/),
    viewBox: text.match(/viewBox="([^"]+)"/)[1].split(' ').map(Number),
    outlineBox: [Math.max(...xs) - Math.min(...xs), Math.max(...ys) - Math.min(...ys)],
    fontSize: number(/\.scale-note\{[^}]*font-size:([\d.]+)px/),
    noteLines: [...text.matchAll(/<tspan[^>]*>([^<]*)<\/tspan>/g)].map(([, line]) => line),
  };
}

async function exportSvg(page) {
  const [download] = await Promise.all([page.waitForEvent('download'), page.getByTestId('export-svg').click()]);
  return readSvg(readFileSync(await download.path(), 'utf8'));
}

test('the torso panel is guessed in metres, shown and exported at its real size, note legible', async ({ page }) => {
  const pageErrors = await openApp(page);
  const loaded = await uploadFile(page, meshPath(TORSO));
  expect(loaded.ok).toBe(true);
  expect(loaded.info.unitGuess).toEqual({ name: 'm', mmPerUnit: 1000 });
  await page.getByTestId('mode-flatten').click();
  await page.locator('#flatten-axis').selectOption('y');
  await page.getByTestId('flatten-run').click();
  await expect(page.getByTestId('export-svg')).toBeEnabled();

  await expect(page.locator('#flatten-unit')).toHaveValue('guess');
  await expect(page.locator('#flatten-unit option[value=guess]')).toHaveText('Guessed: metres');
  await expect(page.getByTestId('pattern-unit-note')).toContainText('Guessed from the mesh');
  const size = page.getByTestId('pattern-size');
  await expect(size).toContainText('1 unit = 1000 mm');
  const shown = [Number(await size.getAttribute('data-width-mm')), Number(await size.getAttribute('data-height-mm'))];
  // A torso front panel: tens of centimetres, not millimetres.
  expect(shown[0]).toBeGreaterThan(200);
  expect(shown[1]).toBeGreaterThan(200);
  await saveScreenshot(page, 'pattern-scale-metres');

  const metres = await exportSvg(page);
  // One user unit is one millimetre: width/height in mm equal the viewBox.
  expect(metres.viewBox).toEqual([0, 0, metres.width, metres.height]);
  expect(metres.outlineBox[0]).toBeCloseTo(shown[0], 0);
  expect(metres.outlineBox[1]).toBeCloseTo(shown[1], 0);
  expect(metres.fontSize).toBe(4);
  expect(metres.noteLines[0]).toContain('1 model unit = 1000.000 mm');
  // Which side is up, on the sheet itself (kPatternSide, pattern_export.h).
  expect(metres.noteLines[1]).toBe("Face up: the side the mesh's face normals point to (the outside, for outward normals)");

  // Read as centimetres, the same panel is a hundred times smaller, its note as large and whole.
  await page.locator('#flatten-unit').selectOption('cm');
  await expect(page.getByTestId('pattern-unit-note')).toBeHidden();
  await expect(size).toContainText('1 unit = 10 mm');
  expect(Number(await size.getAttribute('data-width-mm'))).toBeCloseTo(shown[0] / 100, 3);
  const centimetres = await exportSvg(page);
  expect(centimetres.outlineBox[0]).toBeCloseTo(shown[0] / 100, 1);
  expect(centimetres.fontSize).toBe(4);
  expect(centimetres.noteLines.length).toBe(3);  // the scale, the side shown, the request
  // The sheet is wide enough for the longest note line (0.6 em per character) plus its margins.
  const longest = Math.max(...centimetres.noteLines.map((line) => line.length));
  expect(centimetres.width).toBeGreaterThanOrEqual(0.6 * 4 * longest + 20 - 0.01);

  // At a micrometre per unit the panel is under a millimetre: its size is
  // said in significant digits (it said "0.00 mm × 0.00 mm").
  await page.locator('#flatten-unit').selectOption('custom');
  const perUnit = page.locator('#flatten-mmPerUnit');
  await perUnit.fill('0.001');
  await perUnit.press('Enter');
  await expect(size).toContainText('1 unit = 0.001 mm');
  const tinyWidth = Number(await size.getAttribute('data-width-mm'));
  expect(tinyWidth).toBeCloseTo(shown[0] / 1e6, 9);
  await expect(size).toContainText(`${Number(tinyWidth.toPrecision(3))} mm ×`);
  expect(pageErrors).toEqual([]);
});
