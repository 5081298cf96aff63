// The user's display preferences the style sheets honour: reduced motion (the
// indeterminate progress bar stands still) and forced colours (Windows High
// Contrast: the pressed tool, the selected mode tab and the progress fill
// stay told apart, where backgrounds and border colours are the system's).
import { expect, openApp, test } from './support.mjs';

// The indeterminate bar's fill, shown as during a solve whose length is unknown.
const indeterminateFill = (page) => page.evaluate(() => {
  document.querySelector('[data-testid=progress]').hidden = false;
  const bar = document.querySelector('.progress-bar');
  bar.classList.add('indeterminate');
  bar.firstChild.style.width = ''; // as status-bar.js leaves it when no fraction is known
  const style = getComputedStyle(bar.firstChild);
  return { animation: style.animationName, width: bar.firstChild.getBoundingClientRect().width, barWidth: bar.getBoundingClientRect().width };
});

test('with reduced motion the indeterminate progress bar does not move', async ({ page }) => {
  const pageErrors = await openApp(page);
  expect((await indeterminateFill(page)).animation).toBe('progress-slide');
  await page.emulateMedia({ reducedMotion: 'reduce' });
  const still = await indeterminateFill(page);
  expect(still.animation).toBe('none');
  expect(still.width).toBeCloseTo(still.barWidth, 0);
  expect(pageErrors).toEqual([]);
});

test('in forced colours the pressed tool, the selected tab and the progress fill stand out', async ({ page }) => {
  const pageErrors = await openApp(page);
  await page.emulateMedia({ forcedColors: 'active' });
  const looks = await page.evaluate(() => {
    // The text and border colours: the background's 20 % accent became
    // 20 % of the system's Canvas colour, the same as the others' to the eye.
    const look = (selector) => {
      const style = getComputedStyle(document.querySelector(selector));
      return `${style.color} ${style.borderTopColor}`;
    };
    document.querySelector('[data-testid=progress]').hidden = false;
    document.querySelector('.progress-fill').style.width = '50%';
    return {
      pressedTool: look('.tool-button[aria-pressed="true"]'),
      otherTool: look('.tool-button[aria-pressed="false"]'),
      selectedTab: look('.mode-tab[aria-selected="true"]'),
      otherTab: look('.mode-tab[aria-selected="false"]'),
      fill: getComputedStyle(document.querySelector('.progress-fill')).backgroundColor,
      bar: getComputedStyle(document.querySelector('.progress-bar')).backgroundColor,
    };
  });
  expect(looks.pressedTool).not.toBe(looks.otherTool);
  expect(looks.selectedTab).not.toBe(looks.otherTab);
  expect(looks.fill).not.toBe(looks.bar);
  expect(pageErrors).toEqual([]);
});
