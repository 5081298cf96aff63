// Vite build of the Anisoform page and its examples (dist/examples/): a
// self-contained static site in dist/ (relative base, so it works from any
// folder of any static server).
import { defineConfig } from 'vite';
import { fileURLToPath } from 'node:url';

const repoRoot = fileURLToPath(new URL('..', import.meta.url));
// The examples import the package as an embedder would, by its name; here the
// name points at the package build (scripts/build-lib.mjs, run before this).
const packageDir = fileURLToPath(new URL('./dist-lib', import.meta.url));

export default defineConfig({
  base: './',
  // The solver worker imports the Emscripten ES module; module workers keep
  // that import as is.
  worker: { format: 'es' },
  // GLSL chunks live in the top-level shaders/ folder, outside web/.
  server: { fs: { allow: [repoRoot] } },
  resolve: { alias: [{ find: /^anisoform(\/.*)?$/, replacement: `${packageDir}$1` }] },
  build: {
    outDir: 'dist',
    emptyOutDir: true,
    target: 'es2022',
    // three.js alone is ~600 KB minified; a split would not make the first
    // frame faster, since everything is needed to show the mesh.
    chunkSizeWarningLimit: 1500,
    rollupOptions: {
      input: {
        site: fileURLToPath(new URL('./index.html', import.meta.url)),
        configurator: fileURLToPath(new URL('./examples/configurator.html', import.meta.url)),
        embedding: fileURLToPath(new URL('./examples/embedding.html', import.meta.url)),
      },
    },
  },
});
