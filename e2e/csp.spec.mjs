// The site under the strict Content-Security-Policy with no request leaving
// its origin: load, edit, export, flatten and export a pattern, with no
// violation anywhere (page or solver worker) and no off-origin request. Then
// the witnesses are shown to work, so the check cannot pass vacuously: an
// inline script and eval are refused and reported, a cross-origin fetch is
// refused by the policy, and a navigation to another origin is caught and
// aborted by the guard (csp-guard.mjs, which every spec runs under).
import { CONTENT_SECURITY_POLICY, CSP_REPORT_PATH } from '../scripts/serve-static.mjs';
import { expect, meshPath, openApp, test, uploadFile } from './support.mjs';
import { origin } from './server.mjs';

const TORSO = 'open/human_woman_torso_front_patch.obj';

// Up to 5 s: the browser posts its reports when it gets to them, later with
// the other worker's browser busy on the same two cores.
async function takeUntil(page, csp, done) {
  const seen = { events: [], reports: [], offOrigin: [], unprotected: [] };
  for (let attempt = 0; attempt < 100 && !done(seen); attempt++) {
    await page.waitForTimeout(50);
    const taken = await csp.take();
    for (const key of Object.keys(seen)) seen[key].push(...taken[key]);
  }
  return seen;
}

test('load, edit, export and flatten run under the strict CSP with no request leaving the origin', async ({ page, csp }) => {
  const [document] = await Promise.all([page.waitForResponse(`${origin}/`), openApp(page, { navigate: true })]);
  expect(await document.headerValue('content-security-policy')).toContain(CONTENT_SECURITY_POLICY);
  const pageErrors = [];
  page.on('pageerror', (error) => pageErrors.push(error.message));

  const moved = await page.evaluate(async () => {
    const api = window.anisoform;
    const before = api.positions();
    api.select({ sphere: { center: [0, 0.5, 0.6], radius: 0.35 } }, { falloff: 0.15 });
    await api.deform({ method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: [1.3, 1] } });
    const after = api.positions();
    let largest = 0;
    for (let i = 0; i < before.length; i++) largest = Math.max(largest, Math.abs(after[i] - before[i]));
    return largest;
  });
  expect(moved).toBeGreaterThan(0.01);

  // The Export button: bytes from the worker, downloaded through a blob: URL.
  await page.locator('#export-format').selectOption('glb');
  const [download] = await Promise.all([page.waitForEvent('download'), page.getByTestId('export').click()]);
  expect(download.suggestedFilename()).toMatch(/-edited\.glb$/);

  expect((await uploadFile(page, meshPath(TORSO))).ok).toBe(true);
  await page.getByTestId('mode-flatten').click();
  await page.getByTestId('flatten-run').click();
  await expect(page.getByTestId('metric-flipped')).toHaveText('0');
  const [pattern] = await Promise.all([page.waitForEvent('download'), page.getByTestId('export-svg').click()]);
  expect(pattern.suggestedFilename()).toMatch(/\.svg$/);

  // Let late reports arrive before reading them.
  await page.waitForTimeout(300);
  expect(await csp.take()).toEqual({ events: [], reports: [], offOrigin: [], unprotected: [] });
  await expect(page.getByTestId('error')).toBeHidden();
  expect(pageErrors).toEqual([]);
});

test('the policy is enforced and the guard sees violations and off-origin requests', async ({ page, csp }) => {
  await openApp(page);

  // An inline script: refused, seen by the page's listener and reported to the server.
  const inlineRan = await page.evaluate(() => {
    const script = document.createElement('script');
    script.textContent = 'window.__inlineScriptRan = true;';
    document.head.append(script);
    return window.__inlineScriptRan ?? false;
  });
  expect(inlineRan).toBe(false);
  const inline = await takeUntil(page, csp, (seen) => seen.events.length > 0 && seen.reports.length > 0);
  expect(inline.events).toEqual([expect.objectContaining({ directive: 'script-src-elem', blocked: 'inline' })]);
  expect(inline.reports).toEqual([expect.objectContaining({ 'effective-directive': 'script-src-elem', 'blocked-uri': 'inline' })]);

  // eval in the page, in a blob: worker (which inherits the page's policy)
  // and in a same-origin worker script served with the policy: all refused.
  // Only the server's report endpoint hears the workers (their reports need
  // an absolute report-uri, and are dropped if the worker is terminated).
  // (Outside page.evaluate's own call: DevTools lets the evaluated code eval.)
  const evalOutcome = await page.evaluate(() => new Promise((resolve) => setTimeout(() => {
    try {
      resolve(new Function('return "eval ran"')());
    } catch (error) {
      resolve(error.name);
    }
  })));
  expect(evalOutcome).toBe('EvalError');
  const workerSource = 'let outcome; try { outcome = new Function("return \'eval ran\'")(); } catch (error) { outcome = error.name; } postMessage(outcome);';
  const probeWorker = `${origin}/csp-probe-worker.js`;
  await page.route(probeWorker, (route) => route.fulfill({
    contentType: 'text/javascript',
    headers: { 'content-security-policy': `${CONTENT_SECURITY_POLICY}; report-uri ${origin}${CSP_REPORT_PATH}` },
    body: workerSource,
  }));
  const workerOutcomes = await page.evaluate(async ({ source, url }) => {
    const run = (workerUrl) => new Promise((resolve) => {
      const worker = new Worker(workerUrl);
      // Not terminated: that would drop the worker's pending report.
      worker.onmessage = ({ data }) => resolve(data);
      worker.onerror = (event) => resolve(`worker error: ${event.message}`);
    });
    return {
      blob: await run(URL.createObjectURL(new Blob([source], { type: 'text/javascript' }))),
      sameOrigin: await run(url),
    };
  }, { source: workerSource, url: probeWorker });
  expect(workerOutcomes).toEqual({ blob: 'EvalError', sameOrigin: 'EvalError' });
  const evals = await takeUntil(page, csp, (seen) => seen.events.length > 0 && seen.reports.length > 2);
  expect(evals.events).toEqual([expect.objectContaining({ directive: 'script-src', blocked: 'eval' })]);
  // Chromium names a blob: worker's document "blob".
  expect(evals.reports.map((report) => report['document-uri']).sort()).toEqual([`${origin}/`, 'blob', probeWorker].sort());
  for (const report of evals.reports) {
    expect(report).toEqual(expect.objectContaining({ 'effective-directive': 'script-src', 'blocked-uri': 'eval' }));
  }

  // A fetch to another origin: the policy refuses it before any request.
  const fetchOutcome = await page.evaluate(() => fetch('https://example.invalid/mesh.glb').then(() => 'fetched', (error) => error.name));
  expect(fetchOutcome).toBe('TypeError');
  const refused = await takeUntil(page, csp, (seen) => seen.events.length > 0);
  expect(refused.events).toEqual([expect.objectContaining({ directive: 'connect-src', blocked: 'https://example.invalid/mesh.glb' })]);
  expect(refused.offOrigin).toEqual([]);

  // A navigation to another origin (not governed by default-src): the guard
  // records it and aborts it.
  const [popup] = await Promise.all([
    page.waitForEvent('popup'),
    page.evaluate(() => window.open('https://example.invalid/leak')),
  ]);
  const navigated = await takeUntil(page, csp, (seen) => seen.offOrigin.length > 0);
  expect(navigated.offOrigin).toEqual(['https://example.invalid/leak']);
  await popup.close();
  await page.waitForTimeout(300);
  await csp.take();
});

test('the server revalidates: an unchanged file is answered 304 with the policy, any other validator gets it in full', async () => {
  // A 304 keeps the browser's cache entry, and V8's compiled code with it,
  // so a reload does not compile the solver's WASM again (scripts/serve-static.mjs).
  const first = await fetch(`${origin}/index.html`);
  expect(first.status).toBe(200);
  const etag = first.headers.get('etag');
  expect(etag).toBeTruthy();
  expect(first.headers.get('cache-control')).toBe('no-cache');
  const unchanged = await fetch(`${origin}/index.html`, { headers: { 'If-None-Match': etag } });
  expect(unchanged.status).toBe(304);
  expect(unchanged.headers.get('content-security-policy')).toContain(CONTENT_SECURITY_POLICY);
  const other = await fetch(`${origin}/index.html`, { headers: { 'If-None-Match': '"stale"' } });
  expect(other.status).toBe(200);
  expect((await other.text()).length).toBeGreaterThan(0);
});
