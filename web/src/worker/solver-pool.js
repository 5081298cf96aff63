// Solver workers kept warm between modellers (createSolverPool; README,
// "Embedding"). Starting a modeller spends most of its time starting its
// worker: the worker's scripts, the WASM fetched, compiled and instantiated,
// their code not yet optimised (on a CPU-only machine: 0.5 s and 0.71 core-s
// a start, against 0.25 s and 0.32 core-s on a kept worker). A page that
// disposes a modeller and makes another (a configurator switching products,
// a route of a single-page app, the site's in-place start) can hand the first
// one's worker to the second: a modeller made with `solvers: pool` takes an
// idle worker from the pool if one is there, and its dispose() gives the
// worker back, idle (its WASM session freed, its memory kept: WASM memory
// never shrinks), instead of ending it. A worker in the middle of a request
// is ended as before, as is one a cancel stopped.
//
// The pool keeps at most `keep` idle workers, each for at most
// `idleSeconds`; pool.dispose() ends them and any given back later.
import { badParameter } from '../shared/errors.js';

export class SolverPool {
  /** Idle workers, oldest first: {worker, key, timer}. */
  #idle = [];
  #keep;
  #idleMs;
  #disposed = false;

  /**
   * @param {object} [options]
   *   keep: how many idle workers to keep (default 1; 0 keeps none)
   *   idleSeconds: how long an idle worker is kept before it is ended (default 60)
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
    this.#keep = keep;
    // setTimeout fires at once past 2^31 - 1 ms: a longer wait (24.8 days) is that long.
    this.#idleMs = Math.min(idleSeconds * 1000, 2 ** 31 - 1);
  }

  /**
   * An idle worker started from the same worker and WASM URLs (`key`), taken
   * out of the pool; null if there is none.
   */
  take(key) {
    const index = this.#idle.findIndex((entry) => entry.key === key);
    if (index < 0) return null;
    const [{ worker, timer }] = this.#idle.splice(index, 1);
    clearTimeout(timer);
    worker.onerror = null;
    return worker;
  }

  /**
   * Keeps an idle worker (no request in flight, no handlers of its modeller
   * left) for the next modeller; ends it if the pool is full or disposed.
   */
  give(worker, key) {
    if (this.#disposed || this.#keep === 0) {
      worker.terminate();
      return;
    }
    if (this.#idle.length >= this.#keep) this.#end(this.#idle[0]);
    const entry = { worker, key, timer: 0 };
    entry.timer = setTimeout(() => this.#end(entry), this.#idleMs);
    // A worker that fails while idle is not handed out.
    worker.onerror = () => this.#end(entry);
    this.#idle.push(entry);
  }

  #end(entry) {
    const index = this.#idle.indexOf(entry);
    if (index >= 0) this.#idle.splice(index, 1);
    clearTimeout(entry.timer);
    entry.worker.onerror = null;
    entry.worker.terminate();
  }

  /** The number of idle workers kept. */
  get size() {
    return this.#idle.length;
  }

  /** Ends the idle workers; workers given back later are ended at once. */
  dispose() {
    this.#disposed = true;
    for (const entry of [...this.#idle]) this.#end(entry);
  }
}

/** createSolverPool({keep, idleSeconds}): the pool a modeller's `solvers` option takes. */
export function createSolverPool(options) {
  return new SolverPool(options);
}
