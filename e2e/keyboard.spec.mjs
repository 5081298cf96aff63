// The modeller from the keyboard alone (page.keyboard only): "Open…" shows
// the focus of its hidden file input; the 3D view takes the focus and the
// keys (tool keys, [ and ] for the brush radius, arrows to pan); C selects
// the brush's sphere at the surface in the middle of the view without
// painting (Shift+C takes it away), the Select tool's button a box; ? opens
// the shortcut overlay, an accessible dialog that Esc closes; Ctrl+S saves
// the edits and Ctrl+O opens the file picker, not the browser's own.
// A polite live region tells a screen reader when work ends.
import { saveScreenshot } from './artifacts.mjs';
import { evaluateBulk, expect, meshPath, openApp, test, uploadFile } from './support.mjs';

/** Presses Tab until the focused element matches `selector` (at most 80 presses). */
async function tabTo(page, selector) {
  for (let press = 0; press < 80; press++) {
    if (await page.evaluate((wanted) => document.activeElement?.matches(wanted) ?? false, selector)) return;
    await page.keyboard.press('Tab');
  }
  throw new Error(`Tab never reached ${selector}`);
}

const outline = (page, selector) => page.evaluate((wanted) => {
  const style = getComputedStyle(document.querySelector(wanted));
  return `${style.outlineStyle} ${style.outlineWidth}`;
}, selector);

const pressedTool = (page) => page.locator('.tool-button[aria-pressed="true"]').getAttribute('data-testid');

/** The selection the core's region rule should give: 1 inside `inside(point)`, 0 elsewhere. */
const expectSelection = async (page, inside) => {
  const { positions, selection } = await evaluateBulk(page, () => ({
    positions: Array.from(window.anisoform.positions()),
    selection: Array.from(window.anisoform.selection()),
  }));
  const wanted = selection.map((_, v) => (inside(positions.slice(3 * v, 3 * v + 3)) ? 1 : 0));
  const wrong = selection.filter((weight, v) => weight !== wanted[v]).length;
  expect(wrong).toBe(0);
  return wanted.filter((weight) => weight === 1).length;
};

test('Open… shows the focus ring of its hidden file input', async ({ page }) => {
  const pageErrors = await openApp(page);
  const label = 'label[for="file-input"]';
  expect(await outline(page, label)).toMatch(/^none/);
  await tabTo(page, '[data-testid=file-input]');
  expect(await outline(page, label)).toBe('solid 2px');
  await saveScreenshot(page, 'keyboard-open-focus');
  expect(pageErrors).toEqual([]);
});

test('the 3D view takes the focus and the keys: tools, brush radius, pan, region by rule', async ({ page }) => {
  const pageErrors = await openApp(page);
  await tabTo(page, '[data-testid=viewport]');
  expect(await outline(page, '[data-testid=viewport]')).toBe('solid 2px');

  for (const [key, tool] of [['s', 'stretch'], ['t', 'thicken'], ['h', 'shear'], ['r', 'rotate'], ['w', 'twist'], ['a', 'arrows'], ['b', 'select']]) {
    await page.keyboard.press(key);
    expect(await pressedTool(page)).toBe(`tool-${tool}`);
  }
  const radius = page.locator('#brush-radiusPercent');
  await expect(radius).toHaveValue('8');
  await page.keyboard.press(']');
  await page.keyboard.press(']');
  await expect(radius).toHaveValue('12.5');
  await page.keyboard.press('[');
  await expect(radius).toHaveValue('10');

  // C: the brush sphere (10 % of the diagonal) at the surface in the middle of the view.
  const { centre, diagonal } = await page.evaluate(() => {
    const canvas = document.querySelector('[data-testid=viewport]');
    const positions = window.anisoform.positions();
    const min = [Infinity, Infinity, Infinity];
    const max = [-Infinity, -Infinity, -Infinity];
    positions.forEach((value, i) => {
      min[i % 3] = Math.min(min[i % 3], value);
      max[i % 3] = Math.max(max[i % 3], value);
    });
    const hit = window.anisoform.pick([canvas.clientWidth / 2, canvas.clientHeight / 2]);
    return { centre: hit.point, diagonal: Math.hypot(...max.map((value, k) => value - min[k])) };
  });
  const r = 0.1 * diagonal;
  // A hard brush (no soft edge): the region is the sphere itself.
  const softness = page.locator('#brush-softnessPercent');
  await softness.fill('0');
  await softness.press('Enter');
  await page.getByTestId('viewport').focus();
  await page.keyboard.press('c');
  await expect.poll(() => page.evaluate(() => window.anisoform.selection().some((w) => w > 0))).toBe(true);
  const inSphere = (p) => Math.hypot(p[0] - centre[0], p[1] - centre[1], p[2] - centre[2]) <= r;
  const selected = await expectSelection(page, inSphere);
  expect(selected).toBeGreaterThan(20);
  await page.keyboard.press('Shift+C');
  await expect.poll(() => page.evaluate(() => window.anisoform.selection().some((w) => w > 0))).toBe(false);

  // The Select tool's region choice and button, by Tab, Arrow and Enter: a box.
  await tabTo(page, '#brush-region');
  await page.keyboard.press('ArrowDown');
  await expect(page.locator('#brush-region')).toHaveValue('box');
  await tabTo(page, '[data-testid=select-region-centre]');
  await page.keyboard.press('Enter');
  await expect.poll(() => page.evaluate(() => window.anisoform.selection().some((w) => w > 0))).toBe(true);
  const inBox = (p) => p.every((value, k) => Math.abs(value - centre[k]) <= r);
  expect(await expectSelection(page, inBox)).toBeGreaterThan(selected);

  // Arrow keys pan the focused view, Shift+arrows orbit it.
  await tabTo(page, '[data-testid=viewport]');
  const before = await page.evaluate(() => window.anisoform.camera());
  await page.keyboard.press('ArrowLeft');
  const panned = await page.evaluate(() => window.anisoform.camera());
  expect(panned.target).not.toEqual(before.target);
  await page.keyboard.press('Shift+ArrowLeft');
  const orbited = await page.evaluate(() => window.anisoform.camera());
  expect(orbited.target).toEqual(panned.target.map((value) => expect.closeTo(value, 9)));
  expect(orbited.position).not.toEqual(panned.position);
  expect(pageErrors).toEqual([]);
});

test('? opens the shortcut overlay, an accessible dialog that Esc closes', async ({ page }) => {
  const pageErrors = await openApp(page);
  await tabTo(page, '[data-testid=viewport]');
  await page.keyboard.press('?');
  const dialog = page.getByRole('dialog', { name: 'Keyboard shortcuts' });
  await expect(dialog).toBeVisible();
  await expect(dialog.getByRole('row', { name: /^S Stretch tool/ })).toBeVisible();
  await expect(dialog.getByRole('row', { name: /^\[ and \]/ })).toBeVisible();
  expect(await page.evaluate(() => document.activeElement.closest('dialog') !== null)).toBe(true);
  await saveScreenshot(page, 'keyboard-shortcuts');
  // Keys inside the overlay do not reach the modeller.
  await page.keyboard.press('s');
  expect(await pressedTool(page)).toBe('tool-select');
  await page.keyboard.press('Escape');
  await expect(dialog).toBeHidden();
  // Back in the view, the keys work again.
  await page.keyboard.press('s');
  expect(await pressedTool(page)).toBe('tool-stretch');
  expect(pageErrors).toEqual([]);
});

test('Ctrl+S is Save edits, Ctrl+O is Open…, not the browser\'s own', async ({ page }) => {
  const pageErrors = await openApp(page);
  await tabTo(page, '[data-testid=viewport]');
  // Before any edit there is nothing to save: the key says so.
  await page.keyboard.press('Control+s');
  await expect(page.getByTestId('notice')).toContainText('No edits to save yet');
  await page.evaluate(() => window.anisoform.select({ all: true }));
  await page.evaluate(() => window.anisoform.deform({ method: 'anarap', transform: { scale: [1.3, 1] } }));
  await expect(page.getByTestId('notice')).toBeHidden(); // moot now: there are edits to save
  // The keys click the Mesh panel's Save edits button and the Open… file
  // input (what the button does is saved-edits.spec.mjs's); the clicks are
  // counted here in place of the download and the browser's file picker.
  await page.evaluate(() => {
    window.__clicked = [];
    for (const testId of ['save-edits', 'file-input']) {
      document.querySelector(`[data-testid=${testId}]`).click = () => window.__clicked.push(testId);
    }
  });
  const saveEvent = await page.evaluate(() => {
    const event = new KeyboardEvent('keydown', { key: 's', ctrlKey: true, cancelable: true });
    window.dispatchEvent(event);
    return event.defaultPrevented;
  });
  expect(saveEvent).toBe(true); // not the browser's Save page
  await page.keyboard.press('Control+o');
  await page.keyboard.press('Meta+s');
  expect(await page.evaluate(() => window.__clicked)).toEqual(['save-edits', 'file-input', 'save-edits']);
  await page.evaluate(() => {
    for (const testId of ['save-edits', 'file-input']) delete document.querySelector(`[data-testid=${testId}]`).click;
  });
  expect(pageErrors).toEqual([]);
});

test('a screen reader is told when a mesh loads, an edit is solved and a pattern is flattened; a new mesh clears the last solve\'s figures', async ({ page }) => {
  const pageErrors = await openApp(page);
  const announcer = page.getByTestId('announcer');
  await expect(announcer).toHaveAttribute('role', 'status');
  await expect(announcer).toHaveAttribute('aria-live', 'polite');
  await expect(announcer).toHaveText('Loaded spot_triangulated.obj: 2,930 vertices, 5,856 triangles');
  await page.evaluate(async () => {
    await window.anisoform.select({ all: true });
    await window.anisoform.deform({ method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: [1.2, 1] } });
  });
  await expect(announcer).toHaveText(/^Edit solved: \d+ iterations, \d+ ms$/);
  await expect(page.getByTestId('status-solve')).toContainText(/^solve \d/);
  await page.evaluate(async () => {
    await window.anisoform.select({ sphere: { center: [0, 0.2, 0.4], radius: 0.3 } });
    await window.anisoform.flatten({ compress: 0.9, direction: { type: 'global', vector: [1, 0, 0] }, patch: 'selection' });
  });
  await expect(announcer).toHaveText(/^Flattened: compression error [\d.]+ % mean, [\d.]+ % max; cross error [\d.]+ % mean, [\d.]+ % max; \d+ flipped triangles$/);
  // Another mesh: its load is said, and the status bar no longer shows the last mesh's solve.
  expect((await uploadFile(page, meshPath('closed/torus.obj'))).ok).toBe(true);
  await expect(announcer).toHaveText(/^Loaded torus.obj: [\d,]+ vertices, [\d,]+ triangles$/);
  await expect(page.getByTestId('status-solve')).toHaveText('solve —');
  expect(pageErrors).toEqual([]);
});

test('C selects with the brush\'s soft edge: full weight inside radius x (1 - softness), none beyond the radius', async ({ page }) => {
  const pageErrors = await openApp(page);
  await page.getByTestId('viewport').focus();
  const centre = await page.evaluate(() => {
    const canvas = document.querySelector('[data-testid=viewport]');
    return window.anisoform.pick([canvas.clientWidth / 2, canvas.clientHeight / 2]).point;
  });
  await page.keyboard.press('c'); // the default brush: 8 % radius, soft edge 50 %
  await expect.poll(() => page.evaluate(() => window.anisoform.selection().some((w) => w > 0))).toBe(true);
  const { positions, selection } = await evaluateBulk(page, () => ({
    positions: Array.from(window.anisoform.positions()), selection: Array.from(window.anisoform.selection()) }));
  const extent = [0, 1, 2].map((k) => {
    const values = positions.filter((_, i) => i % 3 === k);
    return Math.max(...values) - Math.min(...values);
  });
  const r = 0.08 * Math.hypot(...extent);
  const distance = (v) => Math.hypot(...[0, 1, 2].map((k) => positions[3 * v + k] - centre[k]));
  const vertices = selection.map((_, v) => v);
  expect(vertices.filter((v) => distance(v) <= 0.5 * r - 1e-6 && selection[v] !== 1)).toEqual([]);
  expect(vertices.filter((v) => distance(v) > r + 1e-6 && selection[v] > 0)).toEqual([]);
  expect(selection.filter((w) => w > 0 && w < 1).length).toBeGreaterThan(5);
  // Shift+C takes all of it away, the soft ring too (32 of 50 vertices
  // stayed selected, at weights up to 0.48), as one undo step.
  await page.keyboard.press('Shift+C');
  await expect.poll(() => page.evaluate(() => window.anisoform.selection().filter((w) => w > 0).length)).toBe(0);
  await page.keyboard.press('Control+z');
  await expect.poll(() => evaluateBulk(page, () => Array.from(window.anisoform.selection()))).toEqual(selection);
  expect(pageErrors).toEqual([]);
});

test('the Deform and Flatten tabs are one Tab stop, and the arrow keys switch between them', async ({ page }) => {
  const pageErrors = await openApp(page);
  const deform = page.getByRole('tab', { name: 'Deform' });
  const flatten = page.getByRole('tab', { name: 'Flatten' });
  await expect(deform).toHaveAttribute('tabindex', '0');
  await expect(flatten).toHaveAttribute('tabindex', '-1');
  await deform.focus();
  await page.keyboard.press('ArrowRight');
  await expect(flatten).toBeFocused();
  await expect(flatten).toHaveAttribute('aria-selected', 'true');
  await expect(page.getByTestId('flatten-run')).toBeVisible();
  await page.keyboard.press('Home');
  await expect(deform).toBeFocused();
  await expect(deform).toHaveAttribute('aria-selected', 'true');
  // Each tab controls its mode's panel (there was no aria-controls, no tabpanel).
  const panelOf = async (tab) => page.locator(`#${await tab.getAttribute('aria-controls')}`);
  const deformPanel = await panelOf(deform);
  await expect(deformPanel).toHaveAttribute('role', 'tabpanel');
  await expect(deformPanel.locator('#direction-source')).toBeVisible();
  await expect(page.getByRole('tabpanel', { name: 'Deform' })).toBeVisible();
  const flattenPanel = await panelOf(flatten);
  await expect(flattenPanel).toBeHidden();
  await flatten.click();
  await expect(page.getByRole('tabpanel', { name: 'Flatten' }).getByTestId('flatten-run')).toBeVisible();
  await expect(deformPanel).toBeHidden();
  expect(pageErrors).toEqual([]);
});

// Deleting the only edit from the keyboard took its row, and the focus fell
// to <body>: the next Tab started at the top of the page.
test('Delete on the last edit\'s name leaves the focus on the Edits heading, not the page', async ({ page }) => {
  const pageErrors = await openApp(page);
  await page.evaluate(async () => {
    await window.anisoform.select({ all: true });
    await window.anisoform.deform({ method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: [1.2, 1] } });
  });
  const id = await page.evaluate(() => window.anisoform.document().ops[0].id);
  await page.getByTestId(`op-select-${id}`).focus();
  await page.keyboard.press('Delete');
  await expect.poll(() => page.evaluate(() => window.anisoform.document().ops.length)).toBe(0);
  await expect.poll(() => page.evaluate(() => `${document.activeElement.tagName} ${document.activeElement.textContent}`)).toBe('H2 Edits');
  expect(pageErrors).toEqual([]);
});

// In a decimal-comma locale toLocaleString() wrote "2.930" in the status bar,
// the selection panel and the announcer, beside fields and an Edits list
// that write "2,930" and "1.5": one notation now (shared/number-format.js).
test('a German browser sees the counts in the fields\' notation: status bar, selection panel, announcer', async ({ browser }) => {
  const german = await browser.newPage({ locale: 'de-DE' });
  const pageErrors = await openApp(german);
  expect(await german.evaluate(() => (2930).toLocaleString())).toBe('2.930');
  await expect(german.getByTestId('status-mesh')).toHaveText(/^2,930 vertices · 5,856 triangles/);
  await expect(german.getByTestId('announcer')).toHaveText('Loaded spot_triangulated.obj: 2,930 vertices, 5,856 triangles');
  await german.getByTestId('select-all').click();
  await expect(german.locator('.selection-count')).toHaveText('2,930 of 2,930 vertices selected');
  await german.close();
  expect(pageErrors).toEqual([]);
});

// The one polite region also says what changed without a solve: the
// selection's count, a tool chosen by its key, an edit deleted, an undo and
// a redo (none of them was said); the status bar's bar is a progressbar.
test('a screen reader is told the selection count, the tool chosen by key, a deletion, undo and redo; the bar is a progressbar', async ({ page }) => {
  const pageErrors = await openApp(page);
  const announcer = page.getByTestId('announcer');
  await page.getByTestId('select-all').click();
  await expect(announcer).toHaveText('2,930 of 2,930 vertices selected');
  await page.getByTestId('viewport').focus();
  await page.keyboard.press('s');
  await expect(announcer).toHaveText('Stretch tool');
  await page.evaluate(() => window.anisoform.deform({ method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: [1.2, 1] } }));
  const { id, label } = await page.evaluate(() => window.anisoform.document().ops[0]);
  await page.getByTestId(`op-delete-${id}`).click();
  await expect(announcer).toHaveText(`Delete ${label}`);
  await page.getByTestId('viewport').focus();
  await page.keyboard.press('Control+z');
  await expect(announcer).toHaveText(`Undone: Delete ${label}`);
  await page.keyboard.press('Control+Shift+z');
  await expect(announcer).toHaveText(`Redone: Delete ${label}`);
  expect(await page.locator('[role=status][aria-live=polite]').count()).toBe(1);

  const bar = page.getByTestId('progress').getByRole('progressbar', { includeHidden: true });
  await expect(bar).toHaveAttribute('aria-valuemin', '0');
  await expect(bar).toHaveAttribute('aria-valuemax', '100');
  // A flattening reports how far it is: the bar says it as a value.
  await page.evaluate(() => {
    window.__values = [];
    const element = document.querySelector('[data-testid=progress] [role=progressbar]');
    new MutationObserver(() => window.__values.push(element.getAttribute('aria-valuenow'))).observe(element, { attributes: true, attributeFilter: ['aria-valuenow'] });
  });
  expect((await uploadFile(page, meshPath('open/human_woman_torso_front_patch.obj'))).ok).toBe(true);
  await page.evaluate(() => window.anisoform.flatten({ compress: 0.9, direction: { type: 'global', vector: [1, 0, 0] } }));
  const values = await page.evaluate(() => window.__values.filter((value) => value !== null).map(Number));
  expect(values.length).toBeGreaterThan(0);
  expect(values.every((value) => value >= 0 && value <= 100)).toBe(true);
  expect(pageErrors).toEqual([]);
});

// A German or French keyboard types [ and ] with AltGr (Ctrl+Alt to the page
// on Windows), a Mac's with Option: the keys were ignored as shortcuts with
// modifiers. Ctrl+[ alone is still no brush key.
test('[ and ] typed with AltGr or Option change the brush radius', async ({ page }) => {
  const pageErrors = await openApp(page);
  const radius = page.locator('#brush-radiusPercent');
  await expect(radius).toHaveValue('8');
  await page.getByTestId('viewport').focus();
  await page.keyboard.press('Control+Alt+BracketRight'); // Windows AltGr
  await expect(radius).toHaveValue('10');
  await page.getByTestId('viewport').evaluate((canvas) => canvas.dispatchEvent(new KeyboardEvent('keydown', {
    key: ']', code: 'Digit9', modifierAltGraph: true, bubbles: true, cancelable: true })));
  await expect(radius).toHaveValue('12.5');
  await page.keyboard.press('Alt+BracketLeft'); // Option on a Mac layout
  await expect(radius).toHaveValue('10');
  await page.keyboard.press('Control+BracketLeft');
  await expect(radius).toHaveValue('10');
  expect(pageErrors).toEqual([]);
});

// The focused 3D view panned and orbited by key but could not be zoomed.
test('+, = and - zoom the focused 3D view; the shortcut list says so', async ({ page }) => {
  const pageErrors = await openApp(page);
  const distance = () => page.evaluate(() => {
    const { position, target } = window.anisoform.camera();
    return Math.hypot(...position.map((value, k) => value - target[k]));
  });
  await page.getByTestId('viewport').focus();
  const start = await distance();
  await page.keyboard.press('+');
  const closer = await distance();
  expect(closer).toBeCloseTo(start / 1.2, 6);
  await page.keyboard.press('=');
  expect(await distance()).toBeCloseTo(start / 1.44, 6);
  await page.keyboard.press('-');
  await page.keyboard.press('-');
  expect(await distance()).toBeCloseTo(start, 6);
  await page.keyboard.press('?');
  await expect(page.getByTestId('shortcut-dialog')).toContainText('Zoom the view in / out (3D view focused)');
  await page.keyboard.press('Escape');
  expect(pageErrors).toEqual([]);
});

test('C with no surface at the view centre says so and adds no undo step; selection buttons are off while an edit solves', async ({ page }) => {
  // C selected nothing silently and still added "Undo Select"; All and Clear
  // waited behind a solve while Invert acted at once (Clear, Invert ended
  // as Invert, Clear).
  await openApp(page);
  await page.getByTestId('viewport').focus();
  const centreMisses = () => page.evaluate(() => {
    const canvas = document.querySelector('[data-testid=viewport]');
    return window.anisoform.pick([canvas.clientWidth / 2, canvas.clientHeight / 2]) === null;
  });
  for (let i = 0; i < 40 && !(await centreMisses()); i++) await page.keyboard.press('ArrowRight');
  expect(await centreMisses()).toBe(true);
  await page.keyboard.press('c');
  await expect(page.getByTestId('notice')).toContainText('Nothing to select at the view centre');
  expect(await page.evaluate(() => window.anisoform.selection().some((w) => w > 0))).toBe(false);
  await expect(page.getByTestId('undo')).toHaveAttribute('aria-disabled', 'true');
  await page.getByTestId('select-clear').click();
  await expect(page.getByTestId('undo')).toHaveAttribute('aria-disabled', 'true');

  const solving = page.evaluate(() => window.anisoform.deform({ method: 'anarap', tolerance: 0, maxIterations: 10000,
    direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: [1.3, 1] } }).then(() => 'solved', (error) => error.code));
  await expect(page.getByTestId('select-invert')).toHaveAttribute('aria-disabled', 'true');
  await page.getByTestId('select-invert').click({ force: true }); // Playwright waits for an aria-disabled button otherwise
  expect(await page.evaluate(() => window.anisoform.selection().some((w) => w > 0))).toBe(false);
  await page.evaluate(() => window.anisoform.cancel());
  expect(await solving).toBe('cancelled');
  await expect(page.getByTestId('select-invert')).toHaveAttribute('aria-disabled', 'false');
});
