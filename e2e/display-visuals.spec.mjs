// Issue 9 item 9: what the viewport draws besides the surface. A legend for
// the 3D heat maps, with Stretch and Area change in different palettes; flat
// shading and a wireframe overlay; an axis gizmo that turns with the camera;
// arrows drawn solid with heads in a colour that stands out on the orange
// selection; direction glyphs thinned to a screen-space spacing. State is
// read from the DOM (legend text, the canvas's data attributes, the gizmo's
// SVG); screenshots go to e2e/artifacts/. A CPU rasteriser draws without
// multisampling (viewer/software-rendering.js).
import { armChange, canvasCentre, countPixels, expect, openApp, saveScreenshot, test } from './support.mjs';
import { rendererPattern } from './renderer.mjs';

// Viewport pixels matching `kind`: 'red' (the stretch palette's grown), 'blue' (the arrows).
const pixelsOf = async (page, kind) => (await countPixels(page, 'viewport', { [kind]: true })).lit;

test('Stretch and Area change have their own legends and palettes; the range is adaptive or fixed', async ({ page }) => {
  const pageErrors = await openApp(page);
  const legend = page.getByTestId('heatmap-legend');
  await expect(legend).toBeHidden();
  const committed = await armChange(page, 'positions');
  await page.evaluate(() => window.anisoform.deform({
    method: 'anarap', direction: { type: 'global', vector: [1, 0, 0] }, transform: { scale: [1.6, 1] },
  }));
  await committed();

  await page.locator('#display-heatMap').selectOption('stretch');
  await expect(legend).toBeVisible();
  await expect(page.getByTestId('heatmap-legend-title')).toHaveText('Stretch (largest principal stretch)');
  await expect(page.getByTestId('heatmap-legend-range')).toHaveText('Range adapted to the data (95th percentile)');
  const values = page.getByTestId('heatmap-legend-values').locator('span');
  await expect(values.nth(1)).toHaveText('×1.00');
  const stretchBar = await legend.locator('div').first().evaluate((bar) => bar.style.background);
  await expect.poll(() => pixelsOf(page, 'red')).toBeGreaterThan(2000);
  const stretchRed = await pixelsOf(page, 'red');
  await saveScreenshot(page, 'heatmap-stretch');

  await page.locator('#display-heatMap').selectOption('area');
  await expect(page.getByTestId('heatmap-legend-title')).toHaveText('Area change');
  const areaBar = await legend.locator('div').first().evaluate((bar) => bar.style.background);
  expect(areaBar).not.toBe(stretchBar);
  // Area change grows purple, not red.
  await expect.poll(() => pixelsOf(page, 'red')).toBeLessThan(stretchRed / 10);
  await saveScreenshot(page, 'heatmap-area');

  await page.locator('#display-heatRange').selectOption('fixed');
  await expect(page.getByTestId('heatmap-legend-range')).toHaveText('Fixed range');
  await expect(values).toHaveText(['×0.50', '×1.00', '×2.00']);
  await page.locator('#display-heatMap').selectOption('off');
  await expect(legend).toBeHidden();
  expect(pageErrors).toEqual([]);
});

test('flat shading and the wireframe change what is drawn, and say so on the canvas', async ({ page }) => {
  const pageErrors = await openApp(page);
  const canvas = page.getByTestId('viewport');
  await expect(canvas).toHaveAttribute('data-flat-shading', 'false');
  await expect(canvas).toHaveAttribute('data-wireframe', 'false');
  const smooth = await canvas.screenshot();

  await page.getByLabel('Flat shading').check();
  await expect(canvas).toHaveAttribute('data-flat-shading', 'true');
  await expect.poll(async () => Buffer.compare(await canvas.screenshot(), smooth)).not.toBe(0);
  await saveScreenshot(page, 'flat-shading');
  await page.getByLabel('Flat shading').uncheck();
  await expect(canvas).toHaveAttribute('data-flat-shading', 'false');

  await page.getByLabel('Wireframe').check();
  await expect(canvas).toHaveAttribute('data-wireframe', 'true');
  await expect.poll(async () => Buffer.compare(await canvas.screenshot(), smooth)).not.toBe(0);
  await saveScreenshot(page, 'wireframe');
  await page.getByLabel('Wireframe').uncheck();
  await expect(canvas).toHaveAttribute('data-wireframe', 'false');
  expect(pageErrors).toEqual([]);
});

test('on a CPU rasteriser (the one renderer.mjs chose) the viewport draws without multisampling, and says so', async ({ page }) => {
  const pageErrors = await openApp(page);
  const canvas = page.getByTestId('viewport');
  // The context itself, not only the attribute: getContext returns the viewer's.
  const drawn = await canvas.evaluate((element) => {
    const gl = element.getContext('webgl2');
    const info = gl.getExtension('WEBGL_debug_renderer_info');
    return { antialias: gl.getContextAttributes().antialias, renderer: gl.getParameter(info.UNMASKED_RENDERER_WEBGL) };
  });
  expect(drawn.renderer).toMatch(rendererPattern);
  expect(drawn.antialias).toBe(false);
  await expect(canvas).toHaveAttribute('data-antialias', 'false');
  expect(pageErrors).toEqual([]);
});

test('the axis gizmo turns with the camera', async ({ page }) => {
  const pageErrors = await openApp(page);
  const gizmo = page.getByTestId('axis-gizmo');
  await expect(gizmo).toBeVisible();
  await expect(gizmo.locator('g')).toHaveCount(3);
  const xEnd = () => gizmo.locator('g[data-axis=X] line').evaluate((line) => [line.getAttribute('x2'), line.getAttribute('y2')].map(Number));
  const before = await xEnd();
  // Orbit: a drag on the background (the top left corner misses the mesh).
  const { box } = await canvasCentre(page);
  await page.mouse.move(box.x + 30, box.y + 30);
  await page.mouse.down();
  await page.mouse.move(box.x + 230, box.y + 40, { steps: 10 });
  await page.mouse.up();
  await expect.poll(async () => Math.hypot(...(await xEnd()).map((value, k) => value - before[k]))).toBeGreaterThan(5);
  expect(pageErrors).toEqual([]);
});

test('an arrow is drawn solid with a head, in blue over the orange selection; field glyphs are spaced on screen', async ({ page }) => {
  const pageErrors = await openApp(page);
  const canvas = page.getByTestId('viewport');
  const centre = await canvasCentre(page);
  const hit = await page.evaluate((pixel) => window.anisoform.pick(pixel), centre.canvas);
  await page.evaluate((point) => window.anisoform.select({ sphere: { center: point, radius: 0.4 } }), hit.point);
  const blueBefore = await pixelsOf(page, 'blue');

  await page.getByTestId('tool-arrows').click();
  await page.mouse.move(...centre.page);
  await page.mouse.down();
  for (let step = 1; step <= 8; step++) await page.mouse.move(centre.page[0] + 8 * step, centre.page[1]);
  await page.mouse.up();
  await expect(canvas).toHaveAttribute('data-arrow-glyphs', '1');
  await expect.poll(() => pixelsOf(page, 'blue')).toBeGreaterThan(blueBefore + 100);
  await saveScreenshot(page, 'arrow-on-selection');

  // The field over the whole mesh: thinned to about one glyph per 26 px cell, more when zoomed in.
  await page.evaluate(() => window.anisoform.select({ all: true }, { mode: 'subtract' }));
  await page.locator('#direction-source').selectOption('global');
  await expect.poll(async () => Number(await canvas.getAttribute('data-field-glyphs'))).toBeGreaterThan(50);
  const framed = Number(await canvas.getAttribute('data-field-glyphs'));
  const vertices = await page.evaluate(() => window.anisoform.info().vertices);
  expect(framed).toBeLessThan(vertices / 3);
  await saveScreenshot(page, 'direction-glyphs');
  await page.mouse.move(...centre.page);
  await page.mouse.wheel(0, -600);
  await expect.poll(async () => Number(await canvas.getAttribute('data-field-glyphs'))).toBeGreaterThan(1.3 * framed);
  expect(pageErrors).toEqual([]);
});
