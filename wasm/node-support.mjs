// What Node scripts using the WASM module share (the tests in wasm/test/ and
// bench/wasm-bench.mjs): where the module and the shared meshes are, loading
// the module the way Node must (wasmBinary, TOOLCHAIN.md §6), and geometry
// helpers for comparing results.
//
// Kept outside wasm/test/ because `node --test wasm/test/` runs every .mjs
// file under a directory named test.
//
// Environment:
//   ANISO_WASM_DIR    folder with anisoform.mjs/.wasm and the JS layer
//                     (default: web/src/wasm, where the WASM build copies them)
//   ANISO_SHARED_DIR  the shared/ folder (default: ../shared beside the repo)
//   ANISO_CLI         the native `anisoform` CLI (native-parity tests only)
import { existsSync, readFileSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const repoDir = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');

export const wasmDir = path.resolve(process.env.ANISO_WASM_DIR ?? path.join(repoDir, 'web', 'src', 'wasm'));
export const sharedDir = path.resolve(process.env.ANISO_SHARED_DIR ?? path.join(repoDir, '..', 'shared'));
export const meshesDir = path.join(sharedDir, 'meshes');

// {wasm: {Session, memoryUse}, AnisoformError}: the shipped module; with
// {bench: true} the benchmarks' build, which adds LaplacianFloor and
// cappedCylinder (js/anisoform-bench-wasm.mjs).
export async function loadAnisoform({ bench = false } = {}) {
  const [layerName, binaryName, create] = bench
    ? ['anisoform-bench-wasm.mjs', 'anisoform-bench.wasm', 'createAnisoformBenchWasm']
    : ['anisoform-wasm.mjs', 'anisoform.wasm', 'createAnisoformWasm'];
  const layer = path.join(wasmDir, layerName);
  if (!existsSync(layer)) {
    throw new Error(`${layer} does not exist: build the WASM module first, or set ANISO_WASM_DIR`);
  }
  const { [create]: createWasm, AnisoformError } = await import(pathToFileURL(layer).href);
  const wasm = await createWasm({ wasmBinary: readFileSync(path.join(wasmDir, binaryName)) });
  return { wasm, AnisoformError };
}

export function meshPath(relative) {
  return path.join(meshesDir, relative);
}

export function meshBytes(relative) {
  return readFileSync(meshPath(relative));
}

// A new session holding the shared mesh `relative` (e.g. 'closed/spool.off').
export function sessionWith(wasm, relative) {
  const session = new wasm.Session();
  try {
    session.loadMesh(meshBytes(relative), path.basename(relative));
  } catch (error) {
    session.delete();
    throw error;
  }
  return session;
}

export function boundingBox(xyz) {
  const min = [Infinity, Infinity, Infinity];
  const max = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < xyz.length; i += 3) {
    for (let k = 0; k < 3; ++k) {
      min[k] = Math.min(min[k], xyz[i + k]);
      max[k] = Math.max(max[k], xyz[i + k]);
    }
  }
  return { min, max, diagonal: Math.hypot(max[0] - min[0], max[1] - min[1], max[2] - min[2]) };
}

// Largest distance between corresponding vertices of two xyz arrays.
export function maxVertexDistance(a, b) {
  if (a.length !== b.length) throw new Error(`vertex arrays differ in length: ${a.length} vs ${b.length}`);
  let largest = 0;
  for (let i = 0; i < a.length; i += 3) {
    largest = Math.max(largest, Math.hypot(a[i] - b[i], a[i + 1] - b[i + 1], a[i + 2] - b[i + 2]));
  }
  return largest;
}

// The `v x y z` lines of an OBJ file, in order.
export function objVertices(text) {
  const values = [];
  for (const line of text.split('\n')) {
    if (!line.startsWith('v ')) continue;
    const [, x, y, z] = line.trim().split(/\s+/);
    values.push(Number(x), Number(y), Number(z));
  }
  return Float64Array.from(values);
}
