// Playwright end-to-end tests of the built site (web/dist served with the
// strict Content-Security-Policy by scripts/serve-static.mjs), in Debian's
// Chromium: no browser is downloaded.
// Run: npm run build --prefix web && npx --prefix web playwright test -c e2e/playwright.config.mjs
import { defineConfig } from '../web/node_modules/@playwright/test/index.mjs';
import { rendererArgs } from './renderer.mjs';
import { origin, port } from './server.mjs';

export default defineConfig({
  testDir: '.',
  testMatch: '*.spec.mjs',
  // WebGL renders on the CPU; two cores are shared by the browser, the
  // page's worker and the server, so tests run one at a time.
  workers: 1,
  fullyParallel: false,
  timeout: 60_000,
  expect: { timeout: 15_000 },
  reporter: 'list',
  outputDir: '../web/test-results',
  use: {
    baseURL: `${origin}/`,
    viewport: { width: 900, height: 600 },
    launchOptions: {
      executablePath: process.env.ANISO_CHROMIUM ?? '/usr/bin/chromium',
      // Composite on the (CPU-rasterised) GPU as a desktop browser does
      // (renderer.mjs says which rasteriser, and why). Without these, headless
      // Chromium composites in software and reads every WebGL frame back on
      // the page's main thread: 0.6–0.9 s per frame of the 400k-triangle
      // koala, which would measure the missing GPU, not the page.
      args: rendererArgs,
    },
    headless: true,
    trace: 'off',
    screenshot: 'only-on-failure',
  },
  // The built site from the server `scripts/run.sh` uses, with the same
  // Content-Security-Policy header: support.mjs fails a test on any violation
  // (page events and the server's report endpoint, which also hears the
  // worker) and on any request leaving this origin.
  webServer: {
    command: `node ../scripts/serve-static.mjs dist --port ${port}`,
    cwd: '../web',
    url: `${origin}/`,
    reuseExistingServer: !process.env.CI,
    timeout: 30_000,
  },
});
