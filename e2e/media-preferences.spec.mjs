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
