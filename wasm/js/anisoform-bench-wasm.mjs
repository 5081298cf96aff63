// The benchmarks' build of the module (anisoform-bench.mjs, wasm/bench_bindings.cpp):
// the shipped API plus what no user needs, kept out of the
// shipped module and the site:
//   cappedCylinder(approxVertices, radius = 1, height = 4)
//       -> {positions: Float64Array, triangles: Uint32Array} of aniso::capped_cylinder,
//          the benchmarks' closed cylinder (bench/README.md), for Session.setMesh
//   new LaplacianFloor(session, pins)   the cotangent Laplacian of the session's
//       rest mesh factored with `pins` held (constructing it is the precompute);
//       solve() = one 3-column solve; must be delete()d.
//   holdMemory(bytes), releaseHeldMemory()   take memory of the module's heap
//       and keep it, then give all of it back: a nearly full heap for the
//       tests of running out of memory (wasm/test/memory-pressure.test.mjs).
// Used by bench/wasm-bench.mjs and the Node tests.
import createBenchModule from './anisoform-bench.mjs';
import { AnisoformError, callModule, instantiateAnisoform } from './anisoform-wasm.mjs';

export { AnisoformError };

export async function createAnisoformBenchWasm(options = {}) {
  const { api, module, rawSession } = await instantiateAnisoform(createBenchModule, options);

  class LaplacianFloor {
    #raw;

    constructor(session, pins) {
      this.#raw = callModule(() => new module.LaplacianFloor());
      try {
        callModule(() => this.#raw.factor(rawSession(session), pins));
      } catch (error) {
        this.delete();
        throw error;
      }
    }

    solve() {
      callModule(() => this.#raw.solve());
    }

    delete() {
      if (this.#raw !== null) {
        this.#raw.delete();
        this.#raw = null;
      }
    }
  }

  const cappedCylinder = (approxVertices, radius = 1, height = 4) =>
    callModule(() => module.cappedCylinder(approxVertices, radius, height));

  const holdMemory = (bytes) => callModule(() => module.holdMemory(bytes));
  const releaseHeldMemory = () => callModule(() => module.releaseHeldMemory());

  return { ...api, LaplacianFloor, cappedCylinder, holdMemory, releaseHeldMemory };
}
