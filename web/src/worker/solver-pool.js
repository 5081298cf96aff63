// Solver workers (and 3D views' WebGL renderers) kept warm between modellers
// (createSolverPool; README, "Embedding"). Starting a modeller spends most of
// its time starting its worker: the worker's scripts, the WASM fetched,
// compiled and instantiated, their code not yet optimised (on a CPU-only
// machine: 0.5 s and 0.71 core-s a start, against 0.25 s and 0.32 core-s on a
// kept worker). A page that disposes a modeller and makes another (a
// configurator switching products, a route of a single-page app, the site's
// in-place start) can hand the first one's worker to the second: a modeller
// made with `solvers: pool` takes an idle worker from the pool if one is
// there, and its dispose() gives the worker back, idle (its WASM session
// freed, its memory kept: WASM memory never shrinks), instead of ending it. A
// worker in the middle of a request is ended as before, as is one a cancel
// stopped.
//
// The same modeller's view hands on its WebGL renderer (its canvas and GL
// context, its scene's buffers and textures freed): a new context, its
// drawing buffer and shaders cost the page and the GPU process about 0.1
// core-s a start on a CPU rasteriser (20 in-place starts of the site: 7.9-8.7
// -> 5.9-6.4 core-s), and a page that creates and ends contexts nears the
// browser's limit of about 16 live ones sooner.
//
// The pool keeps at most `keep` idle workers and as many renderers, each for
// at most `idleSeconds`; pool.dispose() ends them and any given back later.
import { badParameter } from '../shared/errors.js';
import { IdleShelf } from '../shared/idle-shelf.js';

/** Ends a kept renderer: its GL objects, then its context, given back to the browser now (unless it took it already). */
function endRenderer(renderer) {
  renderer.dispose();
  if (!renderer.getContext().isContextLost()) renderer.forceContextLoss();
}

export class SolverPool {
  #workers;
  #renderers;

  /**
   * @param {object} [options]
   *   keep: how many idle workers (and renderers) to keep (default 1; 0 keeps none)
   *   idleSeconds: how long an idle worker (or renderer) is kept before it is ended (default 60)
   */
  constructor(options = {}) {
    if (options === null || typeof options !== 'object') throw badParameter('createSolverPool: options must be an object');
    const { keep = 1, idleSeconds = 60, ...unknown } = options;
    const extra = Object.keys(unknown);
    if (extra.length > 0) throw badParameter(`createSolverPool: unknown option '${extra[0]}' (options: keep, idleSeconds)`);
    if (!Number.isInteger(keep) || keep < 0) throw badParameter(`createSolverPool: keep must be a whole number of workers, 0 or more, got ${JSON.stringify(keep)}`);
    if (typeof idleSeconds !== 'number' || !(idleSeconds >= 0) || idleSeconds === Infinity) {
      throw badParameter(`createSolverPool: idleSeconds must be a finite number of seconds, 0 or more, got ${JSON.stringify(idleSeconds)}`);
    }
    // setTimeout fires at once past 2^31 - 1 ms: a longer wait (24.8 days) is that long.
    const idleMs = Math.min(idleSeconds * 1000, 2 ** 31 - 1);
    this.#workers = new IdleShelf({
      keep,
      idleMs,
      end: (worker) => worker.terminate(),
      // A worker that fails while idle is not handed out.
      onKept: (worker, drop) => { worker.onerror = drop; },
      onTaken: (worker) => { worker.onerror = null; },
    });
    const lost = new WeakMap();
    this.#renderers = new IdleShelf({
      keep,
      idleMs,
      end: endRenderer,
      // Nor is a renderer whose context the browser takes while it is idle.
      onKept: (renderer, drop) => {
        lost.set(renderer, drop);
        renderer.domElement.addEventListener('webglcontextlost', drop);
      },
      onTaken: (renderer) => renderer.domElement.removeEventListener('webglcontextlost', lost.get(renderer)),
    });
  }

  /**
   * An idle worker started from the same worker and WASM URLs (`key`), taken
   * out of the pool; null if there is none.
   */
  take(key) {
    return this.#workers.take(key);
  }

  /**
   * Keeps an idle worker (no request in flight, no handlers of its modeller
   * left) for the next modeller; ends it if the pool is full or disposed.
   */
  give(worker, key) {
    this.#workers.put(worker, key);
  }

  /** A kept three.js WebGLRenderer made with the same context attributes (`key`); null if there is none. */
  takeRenderer(key) {
    return this.#renderers.take(key);
  }

  /**
   * Keeps a disposed view's renderer (its canvas out of the document, its
   * scene's GL objects freed) for the next modeller's view; ends it if the
   * pool is full or disposed, or if its context is lost.
   */
  giveRenderer(renderer, key) {
    if (renderer.getContext().isContextLost()) endRenderer(renderer);
    else this.#renderers.put(renderer, key);
  }

  /** The number of idle workers kept. */
  get size() {
    return this.#workers.size;
  }

  /** Ends the idle workers and renderers; those given back later are ended at once. */
  dispose() {
    this.#workers.close();
    this.#renderers.close();
  }
}

/** createSolverPool({keep, idleSeconds}): the pool a modeller's `solvers` option takes. */
export function createSolverPool(options) {
  return new SolverPool(options);
}
