// Shared helpers of the end-to-end tests: where the shared meshes are, opening
// the page, loading a file through the real file input, and reading the
// canvas. State is asserted through window.anisoform. `test` carries the CSP
// and same-origin guard of csp-guard.mjs, and hands each test the worker's
// one page, reset to a blank slate (page-pool.mjs).
import { existsSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { expect } from '../web/node_modules/@playwright/test/index.mjs';
import { takeStoppedSite, test } from './page-pool.mjs';

export { expect, test };

const repoRoot = resolve(dirname(fileURLToPath(import.meta.url)), '..');

/** shared/meshes: $ANISO_SHARED_DIR/meshes, or ../shared/meshes beside the repo. */
export const meshesDir = resolve(process.env.ANISO_SHARED_DIR ?? resolve(repoRoot, '..', 'shared'), 'meshes');
if (!existsSync(meshesDir)) {
  throw new Error(`The shared meshes are not at ${meshesDir}: set ANISO_SHARED_DIR to the shared/ folder`);
}
export const meshPath = (relative) => resolve(meshesDir, relative);

/**
 * Opens the app and waits for the default mesh; returns the page errors seen
 * meanwhile and after. A page the last test left on the site gets a new
 * modeller in place (window.anisoformSite.start(): what a reload gives,
 * without loading the code again). The page is loaded anyway with
 * `navigate: true` (tests of the page load itself) and in the tests tagged
 * '@speed', which measure the app as a user's fresh page runs it (its
 * JavaScript not yet optimised by earlier tests).
 * A test that patches the page's globals restores them: the next test's app
 * may start in the same page.
 */
export async function openApp(page, { navigate = test.info().tags.includes('@speed') } = {}) {
  const pageErrors = [];
  page.on('pageerror', (error) => pageErrors.push(error.message));
  if (takeStoppedSite(page) && !navigate) {
    await page.evaluate(() => {
      window.scrollTo(0, 0);
      return window.anisoformSite.start();
    });
  } else {
    await page.goto('/');
  }
  await page.evaluate(() => window.anisoform.ready);
  return pageErrors;
}

/**
 * Picks `path` in the file input and waits for the outcome:
 * {ok: true, info} after a load, {ok: false, message} after an error.
 */
export async function uploadFile(page, path) {
  await page.evaluate(() => {
    window.__nextLoad = new Promise((resolve) => {
      const done = (outcome) => {
        offChange();
        offError();
        resolve(outcome);
      };
      const offChange = window.anisoform.on('change', ({ reason }) => {
        if (reason === 'load') done({ ok: true, info: window.anisoform.info() });
      });
      const offError = window.anisoform.on('error', ({ message }) => done({ ok: false, message }));
    });
  });
  await page.getByTestId('file-input').setInputFiles(path);
  await replaceWorkIfAsked(page);
  return page.evaluate(() => window.__nextLoad);
}

/**
 * With edits made, opening files asks first (ui/replace-dialog.js): answers
 * 'Open without saving'. Call it after files that open (not ones refused
 * outright, as two meshes at once) were given to the picker or dropped.
 */
export async function replaceWorkIfAsked(page) {
  const made = await page.evaluate(() => window.anisoform.document().ops.length).catch(() => 0);
  if (made > 0) await page.getByTestId('replace-open').click();
}

/** An edit that would solve for tens of seconds on the armadillo: the tests of what happens meanwhile stop it. */
export const LONG_EDIT = {
  method: 'anarap',
  direction: { type: 'global', vector: [0, 1, 0] },
  transform: { scale: [1.6, 1] },
  maxIterations: 2000,
  tolerance: 1e-15,
  acceleration: 'none',
};

/**
 * Loads the armadillo with one committed edit, then starts LONG_EDIT and
 * leaves it running: window.__long is its outcome, 'finished' or the
 * rejection's code.
 */
export async function startLongCommit(page) {
  expect((await uploadFile(page, meshPath('closed/armadillo.off'))).ok).toBe(true);
  await page.evaluate(async (edit) => {
    const api = window.anisoform;
    await api.select({ all: true });
    await api.deform({ method: 'andefgrad', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: [1.2, 1] } });
    window.__long = api.deform(edit).then(() => 'finished', (error) => error.code);
  }, LONG_EDIT);
}

/** Selects the vertices above the middle of the mesh's height (y), by the API's box region. */
export async function selectUpperHalf(page) {
  return page.evaluate(() => {
    const xyz = window.anisoform.positions();
    let low = Infinity, high = -Infinity;
    for (let i = 1; i < xyz.length; i += 3) {
      low = Math.min(low, xyz[i]);
      high = Math.max(high, xyz[i]);
    }
    return window.anisoform.select({ box: { min: [-1e9, (low + high) / 2, -1e9], max: [1e9, 1e9, 1e9] } });
  });
}

/** Resolves in the page when the next committed change of `reason` happens. */
export async function armChange(page, reason) {
  await page.evaluate((wanted) => {
    window.__nextChange = new Promise((resolve) => {
      const off = window.anisoform.on('change', (event) => {
        if (event.reason === wanted) {
          off();
          resolve(true);
        }
      });
    });
  }, reason);
  return () => page.evaluate(() => window.__nextChange);
}

/** Number of canvas pixels that differ clearly from the background colour. */
export async function litPixelCount(page) {
  return differingPixelCount(page, 'viewport', [0x1d, 0x21, 0x27]);
}

/** {lit, total}: pixels of the element `testId` that differ clearly from `background` (rgb). */
export async function differingPixelCount(page, testId, background) {
  return countPixels(page, testId, { differsFrom: background });
}

/**
 * {lit, total}: pixels of the element `testId`'s screenshot that match `rule`:
 * {differsFrom: [r, g, b]} (summed difference over 30), {red: true} (red over
 * green and blue by 60) or {blue: true} (blue over red by 80, over green by 60).
 */
export async function countPixels(page, testId, rule) {
  const png = await page.getByTestId(testId).screenshot();
  return page.evaluate(async ({ base64, rule }) => {
    const image = new Image();
    image.src = `data:image/png;base64,${base64}`;
    await image.decode();
    const canvas = new OffscreenCanvas(image.width, image.height);
    const context = canvas.getContext('2d');
    context.drawImage(image, 0, 0);
    const { data } = context.getImageData(0, 0, image.width, image.height);
    const matches = rule.differsFrom
      ? (r, g, b) => Math.abs(r - rule.differsFrom[0]) + Math.abs(g - rule.differsFrom[1]) + Math.abs(b - rule.differsFrom[2]) > 30
      : rule.red
        ? (r, g, b) => r > g + 60 && r > b + 60
        : (r, g, b) => b > r + 80 && b > g + 60;
    let lit = 0;
    for (let i = 0; i < data.length; i += 4) if (matches(data[i], data[i + 1], data[i + 2])) lit++;
    return { lit, total: image.width * image.height };
  }, { base64: png.toString('base64'), rule });
}

/** Centre of the viewport canvas in page coordinates and canvas coordinates. */
export async function canvasCentre(page) {
  const box = await page.getByTestId('viewport').boundingBox();
  return {
    page: [box.x + box.width / 2, box.y + box.height / 2],
    canvas: [box.width / 2, box.height / 2],
    box,
  };
}

/** The lowest and highest of positions (xyz runs) along a unit vector. */
export function rangeAlong(positions, unit) {
  let min = Infinity;
  let max = -Infinity;
  for (let i = 0; i < positions.length; i += 3) {
    const value = positions[i] * unit[0] + positions[i + 1] * unit[1] + positions[i + 2] * unit[2];
    min = Math.min(min, value);
    max = Math.max(max, value);
  }
  return { min, max };
}

/** Extent (max - min) of positions along a unit vector. */
export function extentAlong(positions, unit) {
  const { min, max } = rangeAlong(positions, unit);
  return max - min;
}

/** The loaded mesh's lowest and highest y, and its height (the difference). */
export async function verticalRange(page) {
  const positions = await page.evaluate(() => Array.from(window.anisoform.positions()));
  const { min: low, max: high } = rangeAlong(positions, [0, 1, 0]);
  return { low, high, height: high - low };
}

/**
 * Stretches what lies above the middle height (y) of the loaded mesh by
 * `scale` along y (AnARAP, the selection's border soft over `falloff`) and
 * exports it as `format`: the solver's positions and the file's bytes.
 */
export async function stretchUpperHalfAndExport(page, format, { scale = 1.5, falloff = 0 } = {}) {
  const positions = await page.evaluate(async ([amount, width]) => {
    const api = window.anisoform;
    const rest = api.positions();
    let low = Infinity, high = -Infinity;
    for (let i = 1; i < rest.length; i += 3) {
      low = Math.min(low, rest[i]);
      high = Math.max(high, rest[i]);
    }
    await api.select({ box: { min: [-1e30, (low + high) / 2, -1e30], max: [1e30, 1e30, 1e30] } }, { falloff: width });
    await api.deform({ method: 'anarap', direction: { type: 'global', vector: [0, 1, 0] }, transform: { scale: [amount, 1] } });
    return Array.from(api.positions());
  }, [scale, falloff]);
  return { positions, bytes: await exportedBytes(page, format) };
}

/**
 * The file window.anisoform.export(format) makes, as a Buffer. It crosses
 * from the page as base64 text: as an array of numbers, a 175 kB GLB took
 * 5 s to arrive (each entry serialised apart).
 */
export async function exportedBytes(page, format) {
  const base64 = await page.evaluate(async (as) => {
    const reader = new FileReader();
    const url = new Promise((resolve, reject) => {
      reader.onload = () => resolve(reader.result);
      reader.onerror = () => reject(reader.error);
    });
    reader.readAsDataURL(new Blob([await window.anisoform.export(as)]));
    const text = await url;
    return text.slice(text.indexOf(',') + 1);
  }, format);
  return Buffer.from(base64, 'base64');
}

/** Saves a screenshot of the page for review as e2e/artifacts/NAME.png (git-ignored; CI keeps it). */
export async function saveScreenshot(page, name) {
  await page.screenshot({ path: resolve(repoRoot, 'e2e', 'artifacts', `${name}.png`) });
}

/**
 * From now on, records the kind of every request the page posts to a solver
 * worker (a restarted one too) in window.__posted; resolves a function giving
 * those kinds, from the `from`-th on.
 */
export async function recordWorkerRequests(page) {
  await page.evaluate(() => {
    window.__posted = [];
    const post = Worker.prototype.postMessage;
    Worker.prototype.postMessage = function postMessage(message, ...rest) {
      window.__posted.push(message?.kind);
      return post.call(this, message, ...rest);
    };
  });
  return (from = 0) => page.evaluate((start) => window.__posted.slice(start), from);
}

/**
 * What is wrong with entries 0 to count - 1, as "index: problem" for the
 * first `limit` of them: `problem(i)` says what is wrong with entry i, or
 * nothing. One `expect(failures(...)).toEqual([])` checks a whole array:
 * the runner records every expect() as a step, about 1 ms each, and one per
 * vertex took most of a test's 15 s.
 */
export function failures(count, problem, limit = 5) {
  const found = [];
  for (let i = 0; i < count && found.length < limit; i++) {
    const text = problem(i);
    if (text) found.push(`${i}: ${text}`);
  }
  return found;
}

/** Entries of `actual` further than `tolerance` from those of `expected` (failures' form). */
export function farFrom(actual, expected, tolerance) {
  if (actual.length !== expected.length) return [`length ${actual.length}, expected ${expected.length}`];
  return failures(actual.length, (k) => !(Math.abs(actual[k] - expected[k]) < tolerance) && `${actual[k]}, expected ${expected[k]}`);
}

// Runs in the page: `value` with each long array of numbers (plain or typed)
// replaced by {bulk: type, base64} of its bytes. Self-contained: it is sent
// to the page as source.
function encodeBulk(value) {
  const TYPES = ['Float64Array', 'Float32Array', 'Int32Array', 'Uint32Array', 'Uint8Array', 'Uint16Array', 'Int16Array', 'Int8Array'];
  const toBase64 = (bytes) => {
    let text = '';
    for (let i = 0; i < bytes.length; i += 0x8000) text += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
    return btoa(text);
  };
  const walk = (item) => {
    if (ArrayBuffer.isView(item) && TYPES.includes(item.constructor.name)) {
      return { bulk: item.constructor.name, base64: toBase64(new Uint8Array(item.buffer, item.byteOffset, item.byteLength)) };
    }
    if (Array.isArray(item)) {
      if (item.length >= 32 && item.every((entry) => typeof entry === 'number')) {
        return { bulk: 'Array', base64: toBase64(new Uint8Array(Float64Array.from(item).buffer)) };
      }
      return item.map(walk);
    }
    if (item && typeof item === 'object' && Object.getPrototypeOf(item) === Object.prototype) {
      return Object.fromEntries(Object.entries(item).map(([key, entry]) => [key, walk(entry)]));
    }
    return item;
  };
  return walk(value);
}

function decodeBulk(value) {
  if (Array.isArray(value)) return value.map(decodeBulk);
  if (!value || typeof value !== 'object') return value;
  if (typeof value.bulk === 'string' && typeof value.base64 === 'string' && Object.keys(value).length === 2) {
    const bytes = Buffer.from(value.base64, 'base64');
    const buffer = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
    if (value.bulk === 'Array') return Array.from(new Float64Array(buffer));
    return new globalThis[value.bulk](buffer);
  }
  return Object.fromEntries(Object.entries(value).map(([key, entry]) => [key, decodeBulk(entry)]));
}

/**
 * `target.evaluate(fn, arg)` for results that hold long arrays of numbers
 * (positions, selections): those cross as base64 bytes, exactly, instead of
 * number by number. Playwright checks and serialises each entry of an array
 * apart, in the test runner, the browser and the page: a third of the
 * runner's own time in the document tests. Plain arrays come back as plain
 * arrays of the same doubles (-0 and NaN included), typed ones as their type.
 * Not in the '@speed' tests: one call before the 50k drag (its positions)
 * lowered the drag's figure from 13-19 to 6-8 updates/s in five runs each;
 * why was not found (the page's garbage, collected during the drag, is the
 * guess), so those tests measure the page as page.evaluate leaves it.
 */
export async function evaluateBulk(target, fn, arg) {
  const handle = await target.evaluateHandle(fn, arg);
  try {
    return decodeBulk(await handle.evaluate(encodeBulk));
  } finally {
    await handle.dispose();
  }
}
