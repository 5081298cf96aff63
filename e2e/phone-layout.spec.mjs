// The modeller on a phone (390 × 844 and 320 wide, touch, mobile viewport):
// in Deform and Flatten mode, before and after a solve and with every tool's
// options open, nothing is wider than the window or cut off at its sides,
// every control can be scrolled fully into view and is at least 44 × 44 px,
// and the 3D view keeps a usable height. The side panel is a bottom sheet
// that folds down to its header, giving the view the height.
import { saveScreenshot } from './artifacts.mjs';
import { expect, meshPath, openApp, test, uploadFile } from './support.mjs';

const HEIGHT = 844;
test.use({ viewport: { width: 390, height: HEIGHT }, hasTouch: true, isMobile: true });

// What a finger taps: buttons, fields, the label of the hidden file input,
// whole checkbox rows, the op list's checkboxes (their labels), a notice's Details.
const CONTROLS = 'button, select, input[inputmode="decimal"], label.button, .field-checkbox, summary, .op-toggle';

/** Everything that is wrong with the layout now (empty when fine), and the view sizes. */
const audit = (page) => page.evaluate((controlsSelector) => {
  const width = window.innerWidth;
  const height = window.innerHeight;
  const shown = (element) => element.getClientRects().length > 0 && element.checkVisibility({ visibilityProperty: true });
  const name = (element) => element.dataset.testid || element.getAttribute('aria-label') || element.id
    || element.textContent.trim().slice(0, 24) || element.className || element.tagName;
  const problems = [];
  const scrollWidth = document.documentElement.scrollWidth;
  if (scrollWidth > width) problems.push(`the page is ${scrollWidth} px wide in a ${width} px window`);
  // The part of an element its overflow: hidden ancestors let through (the
  // progress bar's sliding fill is meant to be clipped by the bar).
  const seenSpan = (element) => {
    const box = element.getBoundingClientRect();
    let [left, right] = [box.left, box.right];
    for (let parent = element.parentElement; parent; parent = parent.parentElement) {
      if (!['hidden', 'clip'].includes(getComputedStyle(parent).overflowX)) continue;
      const clip = parent.getBoundingClientRect();
      [left, right] = [Math.max(left, clip.left), Math.min(right, clip.right)];
    }
    return { left, right, width: box.width };
  };
  for (const element of document.querySelectorAll('.app, .app *')) {
    if (!shown(element)) continue;
    const box = seenSpan(element);
    if (box.width > 0 && (box.left < -0.5 || box.right > width + 0.5)) {
      problems.push(`${name(element)} spans x ${box.left.toFixed(0)}..${box.right.toFixed(0)}`);
    }
    if (element.scrollWidth > element.clientWidth + 1 && ['auto', 'scroll'].includes(getComputedStyle(element).overflowX)) {
      problems.push(`${name(element)} scrolls sideways (${element.scrollWidth} > ${element.clientWidth})`);
    }
  }
  for (const control of document.querySelectorAll(controlsSelector)) {
    if (!shown(control) || !control.closest('.app')) continue;
    control.scrollIntoView({ block: 'nearest', inline: 'nearest' });
    const box = control.getBoundingClientRect();
    if (box.left < -0.5 || box.top < -0.5 || box.right > width + 0.5 || box.bottom > height + 0.5) {
      problems.push(`${name(control)} cannot be scrolled fully into view (${box.left.toFixed(0)},${box.top.toFixed(0)} ${box.width.toFixed(0)}×${box.height.toFixed(0)})`);
    }
    if (box.width < 44 || box.height < 44) problems.push(`${name(control)} is ${box.width.toFixed(0)}×${box.height.toFixed(0)} px`);
  }
  if (window.scrollX !== 0 || window.scrollY !== 0) problems.push(`the page scrolled to ${window.scrollX},${window.scrollY}`);
  const heightOf = (selector) => document.querySelector(selector)?.getBoundingClientRect().height ?? 0;
  return { problems, view: heightOf('[data-testid=viewport]'), pattern: heightOf('[data-testid=pattern-canvas]') };
}, CONTROLS);

async function expectTidy(page, label) {
  const result = await audit(page);
  expect(result.problems, label).toEqual([]);
  return result;
}

for (const width of [390, 320]) {
  test(`${width} px, Deform: nothing cut off, 44 px targets, before and after a solve, sheet folds`, async ({ page }) => {
    await page.setViewportSize({ width, height: HEIGHT });
    const pageErrors = await openApp(page);
    const fresh = await expectTidy(page, 'fresh page');
    expect(fresh.view).toBeGreaterThan(0.35 * HEIGHT);
    // The status bar keeps its height as its texts change (the view above it too).
    const statusHeight = () => page.locator('.status-bar').evaluate((bar) => bar.getBoundingClientRect().height);
    const freshStatus = await statusHeight();

    // Cut off by its iteration cap: the status line's longest text.
    await page.evaluate(() => window.anisoform.deform({
      method: 'anarap', direction: { type: 'global', vector: [1, 0, 0] }, transform: { scale: [1.3, 1] }, maxIterations: 2,
    }));
    await expect(page.getByTestId('status-solve')).toContainText(/^solve \d.* · cap reached$/);
    await expect(page.getByTestId('status-fps')).not.toBeEmpty();
    const solved = await expectTidy(page, 'after a solve');
    expect(await statusHeight()).toBe(freshStatus);
    expect(solved.view).toBe(fresh.view);
    // While a solve runs, with its progress and Cancel shown, too; Cancel
    // is tapped fully (44 px) and stops it.
    const running = page.evaluate(() => window.anisoform.deform({ method: 'anarap', tolerance: 0, maxIterations: 10000,
      direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: [1.2, 1] } }).catch((error) => error.code));
    await expect(page.getByTestId('cancel-solve')).toBeVisible();
    expect(await statusHeight()).toBe(freshStatus);
    await expectTidy(page, 'while solving');
    await page.getByTestId('cancel-solve').tap();
    expect(await running).toBe('cancelled');
    for (const tool of ['select', 'stretch', 'thicken', 'shear', 'rotate', 'twist', 'arrows']) {
      await page.getByTestId(`tool-${tool}`).tap();
      await expectTidy(page, `${tool} options`);
    }
    // The op of the solve, opened in the Edits list, with its amount field.
    await page.locator('.op-label').first().tap();
    await expectTidy(page, 'an op opened in the edit list');
    await page.getByTestId('tool-stretch').scrollIntoViewIfNeeded();
    await saveScreenshot(page, `phone-${width}-deform`);

    const toggle = page.getByTestId('sheet-toggle');
    await expect(toggle).toHaveAttribute('aria-expanded', 'true');
    await toggle.tap();
    await expect(toggle).toHaveAttribute('aria-expanded', 'false');
    await expect(page.getByTestId('tool-stretch')).toBeHidden();
    const folded = await expectTidy(page, 'sheet folded');
    expect(folded.view).toBeGreaterThan(0.75 * HEIGHT);
    await saveScreenshot(page, `phone-${width}-deform-folded`);
    await toggle.tap();
    await expect(page.getByTestId('tool-stretch')).toBeVisible();
    expect(pageErrors).toEqual([]);
  });

  test(`${width} px, Flatten: nothing cut off, 44 px targets, before and after flattening`, async ({ page }) => {
    await page.setViewportSize({ width, height: HEIGHT });
    const pageErrors = await openApp(page);
    expect((await uploadFile(page, meshPath('open/human_woman_torso_front_patch.obj'))).ok).toBe(true);
    await page.getByTestId('mode-flatten').tap();
    await expect(page.getByTestId('pattern-view')).toBeVisible();
    const before = await expectTidy(page, 'flatten mode');
    console.log(`${width} px flatten: 3D view ${before.view} px, pattern ${before.pattern} px high`);
    expect(before.view).toBeGreaterThan(0.2 * HEIGHT);
    expect(before.pattern).toBeGreaterThan(0.2 * HEIGHT);

    await page.getByTestId('flatten-run').tap();
    await expect(page.getByTestId('metric-flipped')).toHaveText('0');
    await expect(page.getByTestId('status-fps')).not.toBeEmpty();
    await expectTidy(page, 'after flattening');
    await saveScreenshot(page, `phone-${width}-flatten`);

    await page.getByTestId('sheet-toggle').tap();
    const folded = await expectTidy(page, 'sheet folded');
    expect(folded.view).toBeGreaterThan(0.35 * HEIGHT);
    expect(folded.pattern).toBeGreaterThan(0.35 * HEIGHT);
    await saveScreenshot(page, `phone-${width}-flatten-folded`);
    expect(pageErrors).toEqual([]);
  });
}

test('390 px: a long warning shows three lines and More, which opens the rest and folds it again', async ({ page }) => {
  // The hand's flatten warning ran to eight lines over the 3D view's top.
  const pageErrors = await openApp(page);
  expect((await uploadFile(page, meshPath('open/hand_lowres.obj'))).ok).toBe(true);
  // A short notice first (the flattening does not clear it).
  await page.keyboard.press('Control+s');
  const notice = page.getByTestId('notice');
  await expect(notice).toContainText('No edits to save yet');  // three lines at most: no More
  await expect(notice.getByTestId('message-more')).toBeHidden();
  await page.getByTestId('mode-flatten').tap();
  await page.getByTestId('flatten-run').tap();
  const warning = page.getByTestId('warning');
  await expect(warning).toContainText('This patch needs a dart or a cut here');
  const text = warning.locator('.message-text');
  const lineHeight = await text.evaluate((element) => Number.parseFloat(getComputedStyle(element).lineHeight));
  const heightOf = async () => (await text.boundingBox()).height;
  expect(await heightOf()).toBeLessThanOrEqual(3 * lineHeight + 1);
  // The warning comes before the notice, and its first lines show in
  // the short view: below the notice, demosthenes' warning was a strip with
  // no text.
  await expect(notice).toBeVisible();
  expect((await warning.boundingBox()).y).toBeLessThan((await notice.boundingBox()).y);
  const shown = await page.locator('.viewport-messages').boundingBox();
  expect((await text.boundingBox()).y + 2 * lineHeight).toBeLessThanOrEqual(shown.y + shown.height);
  const more = warning.getByTestId('message-more');
  await expect(more).toHaveText('More');
  await expect(more).toHaveAttribute('aria-expanded', 'false');
  // More is shown whole in the 240 px Flatten view, and a tap at its centre
  // reaches it (it was cut off below the messages' box, the view under it).
  const reachable = () => more.evaluate((button) => {
    const box = button.getBoundingClientRect();
    const clip = button.closest('.viewport-messages').getBoundingClientRect();
    const hit = document.elementFromPoint(box.x + box.width / 2, box.y + box.height / 2);
    return { inside: box.top >= clip.top && box.bottom <= clip.bottom, hit: button.contains(hit) };
  });
  expect(await reachable()).toEqual({ inside: true, hit: true });
  await expectTidy(page, 'a long warning, folded');
  await more.tap();
  await expect(more).toHaveText('Less');
  await expect(more).toHaveAttribute('aria-expanded', 'true');
  expect(await heightOf()).toBeGreaterThan(5 * lineHeight);
  await expectTidy(page, 'a long warning, opened');
  // Opened, the messages end above the 3D heat map's legend (they reached
  // down over its title) and scroll within what is left.
  const legend = await page.getByTestId('heatmap-legend').boundingBox();
  const messages = await page.locator('.viewport-messages').boundingBox();
  expect(legend).not.toBeNull();
  expect(messages.y + messages.height).toBeLessThanOrEqual(legend.y);
  await saveScreenshot(page, 'phone-390-warning-opened');
  await more.tap();
  await expect(more).toHaveText('More');
  expect(await heightOf()).toBeLessThanOrEqual(3 * lineHeight + 1);
  expect(pageErrors).toEqual([]);
});

// 400 % zoom of a 1280 × 800 window is 320 × 200 CSS px, 200 % is 640 × 400.
// The sheet's header sticks to its top: a control Tab or Shift+Tab focuses
// is scrolled in below it, not under it; and the visually hidden file input
// (outside the sheet's scroller) made the page itself scroll 87 px.
for (const [zoom, width, height] of [['400 %', 320, 200], ['200 %', 640, 400]]) {
  test(`${zoom} zoom (${width} × ${height}): no control is focused under the sheet's header, the page does not scroll`, async ({ page }) => {
    await page.setViewportSize({ width, height });
    const pageErrors = await openApp(page);
    const overflow = await page.evaluate(() => ({
      height: document.documentElement.scrollHeight - window.innerHeight,
      width: document.documentElement.scrollWidth - window.innerWidth,
    }));
    expect(overflow).toEqual({ height: 0, width: 0 });
    const hidden = [];
    const focusedUnderHeader = () => page.evaluate(() => {
      const element = document.activeElement;
      const panel = element?.closest('.side-panel');
      if (!panel || element.closest('.brand')) return null;
      const header = panel.querySelector('.brand').getBoundingClientRect();
      const box = element.getBoundingClientRect();
      return box.top < header.bottom - 0.5 ? `${element.id || element.dataset.testid || element.textContent.trim().slice(0, 20)} top ${box.top.toFixed(0)} < header ${header.bottom.toFixed(0)}` : null;
    });
    await page.getByTestId('mode-deform').focus();
    for (let step = 0; step < 25; step++) {
      await page.keyboard.press('Tab');
      const under = await focusedUnderHeader();
      if (under) hidden.push(`Tab: ${under}`);
    }
    for (let step = 0; step < 25; step++) {
      await page.keyboard.press('Shift+Tab');
      const under = await focusedUnderHeader();
      if (under) hidden.push(`Shift+Tab: ${under}`);
    }
    expect(hidden).toEqual([]);
    expect(await page.evaluate(() => [window.scrollX, window.scrollY])).toEqual([0, 0]);
    expect(pageErrors).toEqual([]);
  });
}
