// Playwright end-to-end tests of the built site (web/dist served with the
// strict Content-Security-Policy by scripts/serve-static.mjs), in Debian's
// Chromium headless shell: no browser is downloaded.
// Run: npm run build --prefix web && npx --prefix web playwright test -c e2e/playwright.config.mjs
import { defineConfig } from '../web/node_modules/@playwright/test/index.mjs';
import { rendererArgs } from './renderer.mjs';
import { WORKER_SLOTS, origin, slotOrigins, slotPorts } from './server.mjs';

// The tests whose figures or bounds depend on how fast the solver runs are
// tagged '@speed' (test(title, { tag: '@speed' }, ...)).
const SPEED = /@speed/;

function launchOptions(extraArgs) {
  return {
    // The headless shell (Debian's chromium-headless-shell, what Playwright
    // runs headless by default), not the full browser's headless mode: the
    // same Blink and V8 without the browser's own UI. That UI cost the tests
    // a sixth of their CPU: the browser process drawing its window, and the
    // omnibox popup's WebUI page in a renderer of its own beside every test
    // page (35 of 250 CPU-s in the document and embedding specs). The
    // behaviour tests on two cores: 230 -> 180 s.
    executablePath: process.env.ANISO_CHROMIUM ?? '/usr/lib/chromium/chromium-headless-shell',
    // Composite on the (CPU-rasterised) GPU as a desktop browser does
    // (renderer.mjs says which rasteriser, and why; the behaviour project
    // below turns GPU compositing off again). Without these, headless
    // Chromium composites in software and reads every WebGL frame back on
    // the page's main thread: 0.6–0.9 s per frame of the 400k-triangle
    // koala, which would measure the missing GPU, not the page.
    args: [...rendererArgs, ...extraArgs],
  };
}

export default defineConfig({
  testDir: '.',
  testMatch: '*.spec.mjs',
  // At most two browsers at a time, one per core (the projects below say
  // how many each runs).
  workers: WORKER_SLOTS,
  fullyParallel: false,
  timeout: 60_000,
  expect: { timeout: 15_000 },
  reporter: 'list',
  outputDir: '../web/test-results',
  use: {
    baseURL: `${origin}/`,
    viewport: { width: 900, height: 600 },
    headless: true,
    trace: 'off',
    screenshot: 'only-on-failure',
  },
  // Two projects, two browser flags apart. Each test opens the app afresh, and
  // with it V8 compiles the solver's WASM module: quickly (Liftoff), then
  // again optimised (TurboFan) for its hot functions, about 0.9 s of CPU per
  // page on this machine, in browser contexts that keep no compiled code.
  // The tests that check behaviour, not speed, run with Liftoff only: the
  // same WebAssembly semantics (so the same results, bit for bit), slower
  // solves of their small meshes, and a third less CPU (run alone: 350 ->
  // 236 CPU-s, 208 -> 151 s; in the whole run 185 -> 146 s of its 278 ->
  // 243 s). They also composite the page in software, as Chromium does on a
  // machine without a GPU (WebGL still draws on llvmpipe): compositing every
  // frame of the whole page on the CPU rasteriser cost the GPU process 78
  // CPU-s of the behaviour tests' 275, against 26-33 of 210-266 in
  // software (run alone: 182-191 s against 151-180 s on this noisy host;
  // their small meshes' frames read back cheaply). The tests that measure
  // or bound the solver's speed (frame rates, cancel and round-trip
  // latencies, long tasks, the background factorization), tagged '@speed',
  // run as a user's browser with a GPU does: TurboFan (as the Node tests of
  // the module do) and GPU compositing. (Whole specs at first: the document
  // and configurator specs' other tests, on their own, 34.6 -> 27.1 s with
  // Liftoff only.)
  projects: [
    {
      name: 'behaviour',
      grepInvert: SPEED,
      // Two at a time. One browser, its page and the page's solver worker
      // leave a core idle much of a test (waits for frames, the worker, the
      // server); two keep both busy: 166 -> 142 s for these 117 tests.
      workers: WORKER_SLOTS,
      use: { launchOptions: launchOptions(['--js-flags=--liftoff-only', '--disable-gpu-compositing']) },
    },
    {
      name: 'speed',
      grep: SPEED,
      // One at a time and after the behaviour tests (a dependency: no
      // behaviour test runs beside them), so that what they measure is the
      // app on an otherwise idle machine.
      workers: 1,
      dependencies: ['behaviour'],
      use: { launchOptions: launchOptions([]) },
    },
  ],
  // The built site from the server `scripts/run.sh` uses, with the same
  // Content-Security-Policy header: support.mjs fails a test on any violation
  // (page events and the server's report endpoint, which also hears the
  // worker) and on any request leaving this origin. One server per worker
  // slot, each worker's tests on their own (server.mjs says why); in each
  // worker, `origin` and the baseURL are its slot's.
  webServer: slotPorts.map((slotPort, slot) => ({
    command: `node ../scripts/serve-static.mjs dist --port ${slotPort}`,
    cwd: '../web',
    url: `${slotOrigins[slot]}/`,
    reuseExistingServer: !process.env.CI,
    timeout: 30_000,
  })),
});
