// One browser page per Playwright worker, handed to test after test, instead
// of a new context and page for each. Why: opening a page starts a renderer
// process and its GPU channel, and closing it tears both down: ~0.6 s a test
// on two cores, a sixth of the suite, whatever the test does.
//
// Each test still starts from what a new page would give it:
// - before the test, the page is on about:blank, or on the site with its
//   modeller stopped (openApp then starts a new one in place: support.mjs),
//   with its origin's storage
//   (the autosave's IndexedDB, any web storage, caches) and cookies cleared,
//   its permissions reset (and, before an '@speed' test, the last test's
//   garbage collected: blankSlate), so every test opens the app afresh;
// - after it, the listeners and routes the test added are removed;
// - the viewport goes back to the test's configured one;
// - a test that changed what no reset undoes (init scripts, exposed
//   functions, extra headers, media emulation) gets its page closed, and
//   the next test a new one; so does a test that closed the page itself;
// - a test configured with other context options (test.use: viewport,
//   touch, mobile) gets a page of its own options.
// Pages that specs open themselves (browser.newPage) are theirs, as before.
import { test as guarded } from './csp-guard.mjs';
import { origin } from './server.mjs';

// Page methods whose effect outlives a navigation and has no undo.
const LASTING = ['addInitScript', 'exposeBinding', 'exposeFunction', 'setExtraHTTPHeaders', 'emulateMedia'];

function markLasting(page, pool) {
  for (const name of LASTING) {
    const original = page[name].bind(page);
    page[name] = (...args) => {
      pool.spoiled = true;
      return original(...args);
    };
  }
}

async function closePooled(pool) {
  const { context } = pool;
  Object.assign(pool, { key: null, context: null, page: null, ownListeners: null, cdp: null, spoiled: false });
  await context?.close().catch(() => {});
}

async function openPooled(pool, browser, options, key) {
  await closePooled(pool);
  // browser.newContext is the CSP guard's (csp-guard.mjs): the pooled context is guarded too.
  const context = await browser.newContext(options);
  const page = await context.newPage();
  markLasting(page, pool);
  // Playwright's own listeners, to tell the tests' ones from them.
  const ownListeners = new Map(page.eventNames().map((name) => [name, page.rawListeners(name)]));
  Object.assign(pool, { key, context, page, ownListeners, cdp: await context.newCDPSession(page) });
}

function removeTestListeners({ page, ownListeners }) {
  for (const name of page.eventNames()) {
    const own = ownListeners.get(name) ?? [];
    for (const listener of page.rawListeners(name)) if (!own.includes(listener)) page.off(name, listener);
  }
}

// What a new context would start with: a blank page (the last test's end
// left it on about:blank), an empty origin.
async function blankSlate(pool, viewport, { collectGarbage }) {
  const { page, context, cdp } = pool;
  // The last test's documents are garbage now. Before a test that bounds the
  // page's long tasks (the '@speed' ones) they are collected here, not in a
  // long task in the middle of it (a 314 ms one failed a responsiveness
  // check); the others leave it to V8 (35-70 ms a test saved).
  if (collectGarbage) await cdp.send('HeapProfiler.collectGarbage');
  await cdp.send('Storage.clearDataForOrigin', { origin, storageTypes: 'all' });
  await context.clearCookies();
  await context.clearPermissions();
  const size = page.viewportSize();
  if (viewport && (size?.width !== viewport.width || size?.height !== viewport.height)) {
    await page.setViewportSize(viewport);
  }
}

export const test = guarded.extend({
  pagePool: [
    // Depends on the guard's worker fixture so that its newContext wrapper is in place.
    async ({ browser, cspRecord }, use) => {
      void cspRecord;
      const pool = { key: null, context: null, page: null, ownListeners: null, cdp: null, spoiled: false };
      await use(pool);
      await closePooled(pool);
    },
    { scope: 'worker' },
  ],

  page: async ({ pagePool: pool, browser, baseURL, viewport, hasTouch, isMobile, acceptDownloads }, use, testInfo) => {
    const options = { baseURL, viewport, hasTouch, isMobile, acceptDownloads };
    const key = JSON.stringify(options);
    if (pool.key !== key || pool.spoiled || !pool.page || pool.page.isClosed()) {
      await openPooled(pool, browser, options, key);
    } else {
      await blankSlate(pool, viewport, { collectGarbage: testInfo.tags.includes('@speed') });
    }
    const { page } = pool;
    await use(page);
    if (page.isClosed()) {
      await closePooled(pool);
      return;
    }
    removeTestListeners(pool);
    // Popups and pages the test opened in this context go with it.
    await Promise.all(pool.context.pages().filter((other) => other !== page).map((other) => other.close()));
    await page.unrouteAll({ behavior: 'ignoreErrors' });
    // Leave the app now (its worker and solve end, before the CSP guard's
    // check): the site's modeller is stopped in place, so that the next
    // test's openApp can start a new one without loading the page's code
    // again; any other page goes to about:blank. A page that cannot leave is
    // not handed out again.
    if (!(await stopSite(page))) await page.goto('about:blank').catch(() => closePooled(pool));
  },
});

// Pages left on the site with its modeller stopped (stopSite), until taken.
const stoppedSites = new WeakSet();

/**
 * Stops the site's modeller if `page` shows the site; true if it did. A
 * dispose that throws fails the test; a page that cannot run the stop (it
 * is navigating, or hangs for 5 s) is left to about:blank instead.
 */
async function stopSite(page) {
  if (page.url() !== `${origin}/`) return false;
  const stopping = page.evaluate(() => {
    if (!window.anisoformSite) return { stopped: false };
    try {
      window.anisoformSite.stop();
      return { stopped: true };
    } catch (error) {
      return { stopped: false, error: [error, ...(error?.errors ?? [])].map(String).join('; ') };
    }
  }).catch(() => ({ stopped: false }));
  let timer;
  const timeout = new Promise((resolve) => {
    timer = setTimeout(() => resolve({ stopped: false }), 5_000);
  });
  const { stopped, error } = await Promise.race([stopping, timeout]).finally(() => clearTimeout(timer));
  if (error) throw new Error(`The site's modeller did not stop cleanly: ${error}`);
  if (stopped) stoppedSites.add(page);
  return stopped;
}

/**
 * True once if `page` was handed out still on the site with its modeller
 * stopped (nothing navigated it since): support.mjs's openApp then starts a
 * new modeller instead of loading the page.
 */
export function takeStoppedSite(page) {
  const taken = stoppedSites.delete(page);
  return taken && page.url() === `${origin}/`;
}
