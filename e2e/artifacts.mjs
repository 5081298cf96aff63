// Screenshots the end-to-end tests save for review: e2e/artifacts/<name>.png.
// The folder is git-ignored and outside Playwright's outputDir (which each run
// empties), so the files stay in the tree after `bash scripts/test.sh` for CI
// to keep as artifacts.
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

export const artifactsDir = resolve(dirname(fileURLToPath(import.meta.url)), 'artifacts');

/** Saves what the page shows now as e2e/artifacts/<name>.png. */
export async function saveScreenshot(page, name) {
  await page.screenshot({ path: resolve(artifactsDir, `${name}.png`) });
}
