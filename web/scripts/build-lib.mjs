// Builds the anisoform package into web/dist-lib/ (README "Embedding"):
//   anisoform.js       createModeller and <anisoform-modeller> (ES module;
//                      three and three-mesh-bvh stay imports)
//   solver-worker.js   the solver worker with the WASM loader bundled in
//   anisoform.wasm     the solver
//   style.css          the full UI's styles (ui: 'full')
//   meshopt_decoder.js the meshopt decoder, imported when a GLB needs it
//   index.d.ts, api.d.ts (the api object: src/api/anisoform.d.ts) with the module's
//   anisoform-wasm.d.ts it imports, package.json, README.md
// The worker and the WASM are separate files, found from anisoform.js through
// literal `new URL('./x', import.meta.url)` so that an embedder's bundler
// emits them too and a plain static server serves them; nothing is inlined.
// Two Vite builds: the worker first (Vite's library mode would inline its
// WASM as base64), then the library with the worker left as a URL.
import { copyFile, mkdir, readdir, readFile, rm, writeFile } from 'node:fs/promises';
import { fileURLToPath } from 'node:url';
import { build } from 'vite';

const web = fileURLToPath(new URL('..', import.meta.url));
const outDir = `${web}dist-lib`;
const WORKER_URL = "new URL('./solver-worker.js', import.meta.url)";
const IGNORED_WORKER_URL = "new URL(/* @vite-ignore */ './solver-worker.js', import.meta.url)";
const isThree = (id) => id === 'three' || id.startsWith('three/') || id === 'three-mesh-bvh';

await rm(outDir, { recursive: true, force: true });
await mkdir(outDir, { recursive: true });

// 1. The worker: one ES module beside the WASM it fetches.
await build({
  root: web,
  configFile: false,
  logLevel: 'warn',
  publicDir: false,
  base: './',
  build: {
    outDir,
    emptyOutDir: false,
    target: 'es2022',
    assetsInlineLimit: 0,
    rollupOptions: {
      input: `${web}src/worker/solver-worker.js`,
      preserveEntrySignatures: 'strict',
      output: { format: 'es', entryFileNames: 'solver-worker.js', assetFileNames: '[name][extname]' },
    },
  },
});

// 2. The library. Its worker URL is hidden from Vite's worker bundling (the
// worker is built already) and restored as a plain literal afterwards.
const keepWorkerUrl = {
  name: 'anisoform-keep-worker-url',
  enforce: 'pre',
  transform(code, id) {
    if (!id.endsWith('/worker/solver-client.js')) return null;
    if (!code.includes(WORKER_URL)) this.error(`solver-client.js no longer has ${WORKER_URL}`);
    return code.replace(WORKER_URL, IGNORED_WORKER_URL);
  },
  renderChunk(code, chunk) {
    // The chunks loaded on demand (the glTF decoders) have no worker.
    if (!chunk.isEntry) return null;
    const plain = code.replace(/new URL\(\s*\/\* @vite-ignore \*\/\s*/g, 'new URL(');
    if (!/new Worker\(new URL\(["']\.\/solver-worker\.js["'],\s*import\.meta\.url\s*\)/.test(plain)) {
      this.error(`the library lost its literal worker URL: ${(plain.match(/new Worker\([^;]{0,120}/) ?? ["none"])[0]}`);
    }
    return plain;
  },
};
await build({
  root: web,
  configFile: false,
  logLevel: 'warn',
  publicDir: false,
  base: './',
  plugins: [keepWorkerUrl],
  build: {
    outDir,
    emptyOutDir: false,
    target: 'es2022',
    assetsInlineLimit: 0,
    lib: { entry: `${web}src/embed/index.js`, formats: ['es'], fileName: () => 'anisoform.js', cssFileName: 'style' },
    // The chunks imported on demand (the meshopt decoder, for compressed
    // GLBs) by fixed names, beside anisoform.js.
    rollupOptions: { external: isThree, output: { chunkFileNames: '[name].js' } },
  },
});

// 3. Declarations, README and package.json.
await copyFile(`${web}lib/index.d.ts`, `${outDir}/index.d.ts`);
await copyFile(`${web}lib/README.md`, `${outDir}/README.md`);
// The api's declarations, without the standalone site's globals (window.anisoform, window.anisoformSite).
const apiTypes = await readFile(`${web}src/api/anisoform.d.ts`, 'utf8');
const withoutGlobal = apiTypes.replace(/\ndeclare global \{\n {2}interface Window \{\n {4}anisoform: Anisoform;\n[^]*?\n {2}\}\n\}\n/, '\n');
if (withoutGlobal === apiTypes) throw new Error('build-lib: anisoform.d.ts no longer declares window.anisoform as expected');
// Its request and result types are the module's (the one contract), shipped beside it.
const moduleTypes = "'../wasm/anisoform-wasm'";
if (!withoutGlobal.includes(moduleTypes)) throw new Error(`build-lib: anisoform.d.ts no longer imports ${moduleTypes}`);
await writeFile(`${outDir}/api.d.ts`, withoutGlobal.replaceAll(moduleTypes, "'./anisoform-wasm.js'")); // NodeNext wants the extension
await copyFile(`${web}src/wasm/anisoform-wasm.d.ts`, `${outDir}/anisoform-wasm.d.ts`);
const app = JSON.parse(await readFile(`${web}package.json`, 'utf8'));
const manifest = {
  name: 'anisoform',
  version: app.version,
  description: 'Directional mesh deformation in the browser: an embeddable modeller with a WASM solver in a Web Worker',
  type: 'module',
  module: './anisoform.js',
  types: './index.d.ts',
  exports: {
    '.': { types: './index.d.ts', import: './anisoform.js', default: './anisoform.js' },
    './style.css': './style.css',
    './solver-worker.js': './solver-worker.js',
    './anisoform.wasm': './anisoform.wasm',
    './package.json': './package.json',
  },
  // Every file built here (the on-demand chunks too), but this manifest.
  files: (await readdir(outDir)).filter((file) => file !== 'package.json').sort(),
  sideEffects: ['./anisoform.js', './style.css'],
  dependencies: { three: app.dependencies.three, 'three-mesh-bvh': app.dependencies['three-mesh-bvh'] },
};
await writeFile(`${outDir}/package.json`, `${JSON.stringify(manifest, null, 2)}\n`);
console.log(`build-lib: ${outDir}`);
