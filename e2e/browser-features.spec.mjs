// The test browser runs with Playwright's disabled features and without the
// omnibox popup (browser-features.mjs says why).
import { expect, test } from './support.mjs';
import { omniboxPopupFeatures } from './browser-features.mjs';

const listed = (commandLine, name) => commandLine.split(' ')
  .filter((arg) => arg.startsWith(`--${name}=`))
  .map((arg) => arg.slice(name.length + 3).split(','));

test("the browser keeps Playwright's disabled features and runs no omnibox popup", async ({ browser, page }) => {
  await page.goto('chrome://version');
  const commandLine = await page.locator('#command_line').textContent();
  // Playwright's switch first, ours last: Chromium reads the last one only.
  const switches = listed(commandLine, 'disable-features');
  expect(switches.length, "Playwright's --disable-features, then ours").toBe(2);
  const [playwrights, ours] = switches;
  expect(ours).toEqual(expect.arrayContaining([...playwrights, ...omniboxPopupFeatures]));

  const cdp = await browser.newBrowserCDPSession();
  const { targetInfos } = await cdp.send('Target.getTargets');
  await cdp.detach();
  expect(targetInfos.filter((target) => target.url.startsWith('chrome://omnibox-popup'))).toEqual([]);
  expect(targetInfos.some((target) => target.url === 'chrome://version/')).toBe(true);
});
