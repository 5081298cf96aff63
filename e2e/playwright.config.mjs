// Playwright end-to-end tests of the built site (web/dist served by Python's
// http.server), in Debian's Chromium: no browser is downloaded.
// Run: npm run build --prefix web && npx --prefix web playwright test -c e2e/playwright.config.mjs
import { defineConfig } from '../web/node_modules/@playwright/test/index.mjs';

const port = Number(process.env.ANISO_E2E_PORT ?? 4173);

export default defineConfig({
  testDir: '.',
  testMatch: '*.spec.mjs',
  // SwiftShader renders on the CPU; two cores are shared by the browser, the
  // page's worker and the server, so tests run one at a time.
  workers: 1,
  fullyParallel: false,
  timeout: 60_000,
  expect: { timeout: 15_000 },
  reporter: 'list',
  outputDir: '../web/test-results',
  use: {
    baseURL: `http://127.0.0.1:${port}/`,
    viewport: { width: 900, height: 600 },
    launchOptions: {
      executablePath: process.env.ANISO_CHROMIUM ?? '/usr/bin/chromium',
      // Composite on the (SwiftShader) GPU as a desktop browser does. Without
      // these, headless Chromium composites in software and reads every WebGL
      // frame back on the page's main thread: 0.6–0.9 s per frame of the
      // 400k-triangle koala, which would measure the missing GPU, not the page.
      args: ['--use-angle=swiftshader', '--ignore-gpu-blocklist'],
    },
    headless: true,
    trace: 'off',
    screenshot: 'only-on-failure',
  },
  // The built site from a plain static file server (no special headers): what
  // `scripts/run.sh` serves, and what an embedder's server does.
  webServer: {
    command: `python3 -m http.server ${port} --bind 127.0.0.1 --directory dist`,
    cwd: '../web',
    url: `http://127.0.0.1:${port}/`,
    reuseExistingServer: !process.env.CI,
    timeout: 30_000,
  },
});
