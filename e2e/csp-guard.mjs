// Every end-to-end test runs under the strict Content-Security-Policy and
// with no request leaving the page's origin; a test fails when either is
// broken. support.mjs re-exports `test` from here, so every spec gets it.
//
// Three witnesses, because none sees everything:
// - `securitypolicyviolation` events of every page and frame (an init
//   script passes them to the test through a binding);
// - the server's report endpoint (scripts/serve-static.mjs), the only one
//   that hears violations inside the solver's Web Worker;
// - the browser's requests: any whose origin is not the server's is recorded
//   and aborted, and every same-origin response must carry the policy (so the
//   checks cannot pass against a server that does not send it).
// Every browser context is guarded — the test's own and any a spec opens
// with browser.newPage() in a beforeAll — and whatever happened since the
// previous test's check is charged to the test that is ending (what arrives
// after the last test, to the worker's end).
import { test as base } from '../web/node_modules/@playwright/test/index.mjs';
import { CONTENT_SECURITY_POLICY, CSP_REPORT_PATH, CSP_REPORTS_PATH } from '../scripts/serve-static.mjs';
import { origin } from './server.mjs';

// Violation reports are posted by the browser asynchronously; this is how
// long the worker's end waits for the last ones. A test's end does not wait:
// a report still on its way then is charged to the next test, and the last
// test's to the worker's end (waiting 150 ms after each of 120 tests cost 18 s).
const REPORT_SETTLE_MS = 150;

function problemsIn(left) {
  return [
    ...left.events.map((event) => `CSP violation in the page: ${JSON.stringify(event)}`),
    ...left.reports.map((report) => `CSP violation reported to the server: ${JSON.stringify(report)}`),
    ...left.offOrigin.map((url) => `request leaving ${origin}: ${url}`),
    ...left.unprotected.map(({ url, policy }) => `response without the strict CSP: ${url} (${policy ?? 'no header'})`),
  ];
}

async function takeRecord(record) {
  await Promise.all(record.pending);
  const reports = await serverReports('DELETE');
  const { events, offOrigin, unprotected } = record;
  Object.assign(record, emptyRecord());
  return { events, reports, offOrigin, unprotected };
}

function emptyRecord() {
  return { events: [], offOrigin: [], unprotected: [], pending: [] };
}

// Accepted without a network request: CSP itself decides about these.
function leavesOrigin(url) {
  if (url.startsWith('data:') || url.startsWith('blob:') || url.startsWith('about:')) return false;
  return new URL(url).origin !== origin;
}

async function guardContext(context, record) {
  await context.exposeBinding('__anisoformCspViolation', ({ frame }, violation) => {
    record.events.push({ ...violation, frame: frame.url() });
  });
  await context.addInitScript(() => {
    const report = globalThis.__anisoformCspViolation;
    document.addEventListener('securitypolicyviolation', (event) => {
      report({
        directive: event.effectiveDirective,
        blocked: event.blockedURI,
        source: event.sourceFile,
        line: event.lineNumber,
        sample: event.sample,
      });
    });
  });
  // Each off-origin request once, whether the router or the request event
  // sees it first (the event also covers any the router does not see).
  const noted = new WeakSet();
  const note = (request) => {
    if (noted.has(request)) return;
    noted.add(request);
    record.offOrigin.push(request.url());
  };
  await context.route(
    (url) => leavesOrigin(url.href),
    (route) => {
      note(route.request());
      return route.abort('blockedbyclient');
    },
  );
  context.on('request', (request) => {
    if (leavesOrigin(request.url())) note(request);
  });
  context.on('response', (response) => {
    const url = response.url();
    if (!url.startsWith(`${origin}/`) || new URL(url).pathname === CSP_REPORT_PATH) return;
    record.pending.push(
      response.headerValue('content-security-policy').then(
        (policy) => {
          if (!policy?.startsWith(CONTENT_SECURITY_POLICY)) record.unprotected.push({ url, policy });
        },
        () => {},
      ),
    );
  });
}

async function serverReports(method) {
  let response;
  try {
    response = await fetch(`${origin}${CSP_REPORTS_PATH}`, { method });
  } catch (error) {
    throw new Error(`the CSP report endpoint ${origin}${CSP_REPORTS_PATH} is unreachable: ${error.message}`);
  }
  if (!response.ok) {
    throw new Error(
      `${origin} does not collect CSP reports (${method} ${CSP_REPORTS_PATH}: ${response.status}); ` +
        'serve the site with scripts/serve-static.mjs (is a server from elsewhere reused on this port?)',
    );
  }
  return response.json();
}

export const test = base.extend({
  // Worker scope: guards every context this worker's browser opens.
  cspRecord: [
    async ({ browser }, use) => {
      await serverReports('DELETE');
      const record = emptyRecord();
      const newContext = browser.newContext.bind(browser);
      browser.newContext = async (options) => {
        const context = await newContext(options);
        await guardContext(context, record);
        return context;
      };
      await use(record);
      browser.newContext = newContext;
      await new Promise((resolve) => setTimeout(resolve, REPORT_SETTLE_MS));
      const problems = problemsIn(await takeRecord(record));
      if (problems.length > 0) throw new Error(`after this worker's last test:\n${problems.join('\n')}`);
    },
    { scope: 'worker', auto: true },
  ],

  /**
   * The test's CSP witness. `await csp.take()` returns and forgets what was
   * recorded so far — {events, reports, offOrigin, unprotected} — for a test
   * that provokes a violation on purpose; whatever is left at the test's end
   * fails it.
   */
  csp: [
    async ({ cspRecord }, use) => {
      const take = () => takeRecord(cspRecord);
      await use({ take });
      const problems = problemsIn(await take());
      if (problems.length > 0) throw new Error(problems.join('\n'));
    },
    { auto: true },
  ],
});
