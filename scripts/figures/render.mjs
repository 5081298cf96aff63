// Renders the gallery: reads what the figure scenes recorded (DATA_DIR: one
// JSON per mesh, values.jsonl), draws every picture of gallery.mjs in headless
// Chromium (page.mjs: the app's viewer code, SwiftShader, fixed cameras) and
// writes the PNGs and FIGURES.md. Run by scripts/figures.sh:
//   node scripts/figures/render.mjs DATA_DIR OUT_DIR (docs)
import { readFileSync, writeFileSync, mkdirSync, existsSync, rmSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { FIGURES } from './gallery.mjs';
import { encodePalettePng } from './png8.mjs';

const root = resolve(dirname(fileURLToPath(import.meta.url)), '../..');
const { chromium } = await import(join(root, 'web/node_modules/playwright-core/index.mjs'));

const WIDTH = 320;
const HEIGHT = 240;
const ORIGIN = 'http://gallery.invalid';

const [dataDir, docsDir] = process.argv.slice(2).map((path) => resolve(path));
if (!dataDir || !docsDir) throw new Error('usage: node render.mjs DATA_DIR DOCS_DIR');
const pictureDir = join(docsDir, 'figures');

const values = readValues(join(dataDir, 'values.jsonl'));
checkEveryFigureScene();

// Every value a sentence quotes must have been recorded by this run.
const used = new Set();
const v = (key) => {
  if (!values.has(key)) throw new Error(`the run recorded no value "${key}" (scripts/figures/gallery.mjs)`);
  used.add(key);
  return values.get(key);
};

const meshes = new Map();
const mesh = (name) => {
  if (!meshes.has(name)) {
    const path = join(dataDir, `${name}.json`);
    if (!existsSync(path)) throw new Error(`the run recorded no mesh "${name}" (${path})`);
    meshes.set(name, JSON.parse(readFileSync(path, 'utf8')));
  }
  return meshes.get(name);
};

const browser = await chromium.launch({
  executablePath: process.env.ANISO_CHROMIUM ?? '/usr/lib/chromium/chromium-headless-shell',
  args: ['--use-angle=swiftshader', '--ignore-gpu-blocklist'],
  headless: true,
});
try {
  const page = await browser.newPage({ viewport: { width: WIDTH, height: HEIGHT }, deviceScaleFactor: 1 });
  page.on('pageerror', (error) => { throw error; });
  await page.route(`${ORIGIN}/**`, (route) => route.fulfill(serve(new URL(route.request().url()))));
  await page.goto(`${ORIGIN}/index.html`);
  await page.waitForFunction(() => window.pageReady === true);

  rmSync(pictureDir, { recursive: true, force: true });
  mkdirSync(pictureDir, { recursive: true });
  const sections = [];
  for (const figure of FIGURES) {
    const frames = framesOf(figure);
    const files = [];
    for (const [k, picture] of figure.pictures.entries()) {
      const pixels = await page.evaluate((p) => window.renderPicture(p), {
        mesh: mesh(picture.mesh), width: WIDTH, height: HEIGHT, frame: frames[k],
        direction: figure.view.direction, up: figure.view.up,
        flat: figure.view.flat, wireframe: figure.view.wireframe,
      });
      const file = `fig${figure.id}-${picture.mesh.replace(/^\d+-/, '')}.png`;
      writeFileSync(join(pictureDir, file), encodePalettePng(WIDTH, HEIGHT, Buffer.from(pixels, 'base64')));
      files.push({ file, caption: picture.caption });
    }
    sections.push(section(figure, files));
  }
  const unused = [...values.keys()].filter((key) => !used.has(key));
  if (unused.length > 0) console.warn(`recorded but not quoted: ${unused.join(', ')}`);
  writeFileSync(join(docsDir, 'FIGURES.md'), document(sections));
  console.log(`wrote ${join(docsDir, 'FIGURES.md')} and ${FIGURES.reduce((n, f) => n + f.pictures.length, 0)} pictures`);
} finally {
  await browser.close();
}

function readValues(path) {
  const out = new Map();
  for (const line of readFileSync(path, 'utf8').split('\n')) {
    if (!line.trim()) continue;
    const { key, value } = JSON.parse(line);
    if (out.has(key)) throw new Error(`value "${key}" recorded twice: two scenes share a key`);
    out.set(key, value);
  }
  return out;
}

// The gallery covers every figure scene the tests define ("fig. N" in a
// TEST_CASE name), and shows no figure the tests do not.
function checkEveryFigureScene() {
  const tested = new Set();
  for (const file of ['tests/test_paper_figures.cpp', 'tests/test_figures_post.cpp', 'tests/test_flatten.cpp']) {
    for (const match of readFileSync(join(root, file), 'utf8').matchAll(/TEST_CASE\("[^"]*\bfig\. (\d+)/g)) {
      tested.add(match[1]);
    }
  }
  const shown = new Set(FIGURES.map((figure) => figure.id));
  const missing = [...tested].filter((id) => !shown.has(id));
  const extra = [...shown].filter((id) => !tested.has(id));
  if (missing.length || extra.length) {
    throw new Error(`gallery.mjs and the figure tests differ: not shown ${missing}, not tested ${extra}`);
  }
}

// Per picture, the box the camera fits: around every picture's mesh of the
// figure ('all', so that sizes compare), the first picture's selected
// vertices ('selection', twice their size: some of the surface around them)
// or its own mesh ('own').
function framesOf(figure) {
  const union = (boxes) => ({
    lo: [0, 1, 2].map((k) => Math.min(...boxes.map((b) => b.lo[k]))),
    hi: [0, 1, 2].map((k) => Math.max(...boxes.map((b) => b.hi[k]))),
  });
  const box = (m, only) => {
    const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    for (let i = 0; i < m.positions.length / 3; i++) {
      if (only && !(only[i] > 0)) continue;
      for (let k = 0; k < 3; k++) {
        lo[k] = Math.min(lo[k], m.positions[3 * i + k]);
        hi[k] = Math.max(hi[k], m.positions[3 * i + k]);
      }
    }
    return { lo, hi };
  };
  const pictures = figure.pictures.map((p) => mesh(p.mesh));
  switch (figure.view.frame) {
    case 'all': {
      const frame = union(pictures.map((m) => box(m)));
      return pictures.map(() => frame);
    }
    case 'selection': {
      const { lo, hi } = box(pictures[0], pictures[0].selection);
      const frame = { lo: lo.map((x, k) => x - (hi[k] - x) / 2), hi: hi.map((x, k) => x + (x - lo[k]) / 2) };
      return pictures.map(() => frame);
    }
    case 'own': return pictures.map((m) => box(m));
    default: throw new Error(`figure ${figure.id}: unknown frame ${figure.view.frame}`);
  }
}

function section(figure, files) {
  const header = `| ${files.map((f) => f.caption).join(' | ')} |\n|${files.map(() => '---|').join('')}\n`;
  const row = `| ${files.map((f) => `![${f.caption}](figures/${f.file})`).join(' | ')} |\n`;
  return [
    `## Fig. ${figure.id}: ${figure.title}`,
    '',
    `**Paper.** ${figure.claim}`,
    '',
    `**Scene.** ${figure.scene} Test: ${figure.test}.`,
    '',
    `**Measured.** ${figure.measured(v)}`,
    '',
    header + row,
  ].join('\n');
}

function document(sections) {
  return [
    '# Reproduction gallery',
    '',
    '<!-- Generated by scripts/figures.sh from the figure scenes of the Catch2 suite: do not edit by hand. -->',
    '',
    'Each figure of Colaianni et al. 2017 that the suite reproduces: the paper\'s words (quoted from its text;',
    'figure captions unless marked), the scene (the Catch2 test that checks it; `tests/figure_record.h` hands',
    'its meshes and values to the gallery), the values this run measured, and the pictures (the app\'s own',
    'surface shader and heat palettes, rendered headless in Chromium; orange = selection, its falloff drawn',
    'as iso-lines). The shared meshes stand in for the paper\'s models (MANIFEST.md). What each test asserts,',
    'and where a claim does not hold, is in [FIGURES-measured.md](FIGURES-measured.md). Regenerate with',
    '`bash scripts/figures.sh` (deterministic: a re-run on the same machine writes the same bytes).',
    '',
    ...sections,
  ].join('\n');
}

// The page and its modules: the app's viewer files as they are, the GLSL
// they import with Vite's `?raw` as a module exporting the text, and three.js
// through an import map.
function serve(url) {
  const path = decodeURIComponent(url.pathname);
  if (path === '/index.html') {
    return {
      contentType: 'text/html',
      body: '<!doctype html><html><body style="margin:0">' +
        '<script type="importmap">{"imports": {"three": "/web/node_modules/three/build/three.module.js"}}</script>' +
        '<script type="module" src="/scripts/figures/page.mjs"></script></body></html>',
    };
  }
  const allowed = ['/web/src/viewer/', '/shaders/', '/scripts/figures/', '/web/node_modules/three/build/'];
  if (!allowed.some((prefix) => path.startsWith(prefix))) return { status: 404, body: `not served: ${path}` };
  const text = readFileSync(join(root, path), 'utf8');
  if (url.search === '?raw') return { contentType: 'text/javascript', body: `export default ${JSON.stringify(text)};` };
  return { contentType: 'text/javascript', body: text };
}
