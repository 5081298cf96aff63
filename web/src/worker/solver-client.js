// The page's side of the solver worker: promises per request, progress
// events, and coalescing of live previews.
//
// Coalescing: at most one preview is in flight and at most one waits. A newer
// preview replaces the waiting one (whose promise resolves with null), so
// while the pointer moves faster than the solver, the worker only ever solves
// the latest position, never a backlog of stale ones.
import { CANCELLED_MESSAGE, badParameter } from '../shared/errors.js';
import { EventEmitter } from '../shared/event-emitter.js';
import { urlProblem } from '../shared/url-problem.js';
import { PROGRESS, Request } from './protocol.js';

// Iterations per live preview (a drag's pointer move, a slider's value): one,
// warm-started from the previous preview, so each frame refines the last
// shape towards the new amount and the shape follows the gesture at the
// solver's iteration rate (at 50k vertices in the page: 3 iterations took
// 160-290 ms a preview, 3.4-4.5 shapes/s in a 2 s drag). The core caps a
// preview at kPreviewIterations (session.h) whatever is asked.
const LIVE_PREVIEW_ITERATIONS = 1;

export class SolverError extends Error {
  constructor({ code, message }) {
    super(message);
    this.name = 'SolverError';
    this.code = code;
  }
}

export class SolverClient extends EventEmitter {
  #worker;
  #nextId = 1;
  #pending = new Map();
  #previewInFlight = 0; // the request id of the preview the worker is solving, or 0
  #queuedPreview = null;
  #wasmUrl;
  #workerUrl;
  /** The SolverPool the worker comes from and goes back to, or null. */
  #pool;
  /**
   * True once the worker failed in a way the core did not report (an
   * 'internal' error: a trap, a script error): its state is not known to be
   * sound, so it is not handed to another modeller.
   */
  #tainted = false;
  #disposed = false;
  /** While a restart puts the state back: its promise; else null. */
  #seeding = null;
  /** Requests made meanwhile, sent in order once it is done: {id, kind, payload, transfer, resolve, reject}. */
  #held = [];

  /**
   * workerUrl / wasmUrl: where the solver worker and its WASM are, when not
   * beside this module (a bundler that moves files, a CDN copy of the WASM;
   * the worker must be same-origin). The default `new URL(..., import.meta.url)`
   * stays literal so bundlers find and emit both files.
   * pool: a SolverPool (solver-pool.js) to take an idle worker from and to
   * give the worker back to at dispose().
   */
  constructor({ workerUrl, wasmUrl, pool = null } = {}) {
    super();
    this.#wasmUrl = wasmUrl === undefined ? undefined : String(wasmUrl);
    this.#workerUrl = workerUrl;
    this.#pool = pool;
    this.#worker = this.#spawn(pool?.take(this.#poolKey()) ?? null);
  }

  /** Workers started from the same worker and WASM URLs are interchangeable. */
  #poolKey() {
    return JSON.stringify([this.#workerUrl === undefined ? null : String(this.#workerUrl), this.#wasmUrl ?? null]);
  }

  /** Listens to `kept` (an idle worker from the pool: its init starts a new session), else to a new worker. */
  #spawn(kept = null) {
    const url = this.#workerUrl;
    let worker = kept;
    try {
      // The default's literal form is what bundlers find the worker by.
      worker ??= url === undefined
        ? new Worker(new URL('./solver-worker.js', import.meta.url), { type: 'module' })
        : new Worker(url, { type: 'module' });
    } catch (error) {
      // workerUrl of another origin, or not a URL: thrown at once, as a DOMException.
      throw badParameter(`the solver worker cannot start from ${url}: ${error.message}`);
    }
    worker.onmessage = (event) => this.#receive(event.data);
    worker.onerror = (event) => {
      this.#tainted = true;
      const fail = (reason) => {
        this.#rejectAll(new SolverError({ code: 'internal', message: `The solver stopped: ${reason}` }));
        this.#sendQueuedPreview();
      };
      if (event.message || url === undefined) {
        fail(event.message || 'the worker could not start');
        return;
      }
      // The embedder's script that did not load says nothing of why: the URL is asked.
      urlProblem(url).then((problem) => fail(`the worker could not start from ${url}${problem ? `: ${problem}` : ''}`));
    };
    return worker;
  }

  #rejectAll(failure) {
    for (const { reject } of this.#pending.values()) reject(failure);
    this.#pending.clear();
    this.#previewInFlight = 0;
  }

  /**
   * Stops whatever the worker is solving, at once: the worker is ended and a
   * new one started, requests waiting for the old one reject with code
   * 'cancelled', and `seed(post)` puts the state back (post(kind, payload,
   * transfer) sends a request ahead of any other). Requests made meanwhile
   * wait until the seed is done. Resolves when it is (rejects if it failed).
   */
  restart(seed) {
    if (this.#disposed) return Promise.reject(stoppedByDispose());
    this.#worker.onmessage = null;
    this.#worker.onerror = null;
    this.#worker.terminate();
    const cancelled = new SolverError({ code: 'cancelled', message: CANCELLED_MESSAGE });
    this.#rejectAll(cancelled);
    // Requests held for an earlier restart belong to the work being cancelled.
    for (const { reject } of this.#held) reject(cancelled);
    this.#held = [];
    this.#queuedPreview?.resolve(null);
    this.#queuedPreview = null;
    this.#worker = this.#spawn();
    this.#tainted = false;
    this.emit('progress', { stage: 'restart', message: 'Restarting the solver' });
    const post = (kind, payload = {}, transfer = []) => this.#post(this.#nextId++, kind, payload, transfer);
    const seeding = post(Request.init).then(() => seed(post));
    this.#seeding = seeding;
    const release = () => {
      if (this.#seeding !== seeding) return; // a later restart took over
      this.#seeding = null;
      const held = this.#held;
      this.#held = [];
      for (const { id, kind, payload, transfer, resolve, reject } of held) this.#post(id, kind, payload, transfer).then(resolve, reject);
    };
    seeding.then(release, release);
    return seeding;
  }

  #receive(message) {
    if (message.kind === PROGRESS) {
      // A restart's seed (a reload of the mesh) is announced as the restart.
      if (!this.#seeding) this.emit('progress', { stage: message.stage, message: message.message, fraction: message.fraction });
      return;
    }
    // The next preview goes out before this one's shape is shown: the worker
    // solves it while the page draws, instead of waiting for the page.
    if (message.id === this.#previewInFlight) {
      this.#previewInFlight = 0;
      this.#sendQueuedPreview();
    }
    const pending = this.#pending.get(message.id);
    if (!pending) return;
    this.#pending.delete(message.id);
    if (message.ok) {
      pending.resolve(message.result);
      return;
    }
    if (message.error.code === 'internal') this.#tainted = true;
    pending.reject(new SolverError(message.error));
  }

  request(kind, payload = {}, transfer = []) {
    if (this.#disposed) return Promise.reject(stoppedByDispose());
    // The id now, so that it is known to the caller's bookkeeping at once
    // (the previews'), even when the request waits for a restart's seed.
    const id = this.#nextId++;
    if (!this.#seeding) return this.#post(id, kind, payload, transfer);
    return new Promise((resolve, reject) => this.#held.push({ id, kind, payload, transfer, resolve, reject }));
  }

  #post(id, kind, payload, transfer) {
    if (this.#disposed) return Promise.reject(stoppedByDispose());
    // The WASM location travels with init, the one request that loads it.
    if (kind === Request.init && this.#wasmUrl !== undefined) payload = { ...payload, wasmUrl: this.#wasmUrl };
    return new Promise((resolve, reject) => {
      this.#pending.set(id, { resolve, reject, background: kind === Request.prepareStep });
      this.#worker.postMessage({ id, kind, ...payload }, transfer);
    });
  }

  /**
   * Ends the worker, and with it the WASM session and its memory; requests
   * still waiting reject. With a pool, an idle, sound worker (no request in
   * flight or held, no internal error) goes back to it instead; its next
   * init frees the session.
   */
  dispose() {
    if (this.#disposed) return;
    this.#disposed = true;
    this.#worker.onmessage = null;
    this.#worker.onerror = null;
    if (this.#pool && !this.busy && !this.#tainted) this.#pool.give(this.#worker, this.#poolKey());
    else this.#worker.terminate();
    for (const { reject } of this.#held) reject(stoppedByDispose());
    this.#held = [];
    this.#queuedPreview?.resolve(null);
    this.#queuedPreview = null;
    for (const { reject } of this.#pending.values()) reject(stoppedByDispose());
    this.#pending.clear();
  }

  /**
   * True while a request is waiting for the worker. A part of the background
   * preparation (Request.prepareStep) does not count: it is short, and a
   * worker handed to another modeller finishes it before that one's init,
   * which frees its session.
   */
  get busy() {
    for (const { background } of this.#pending.values()) if (!background) return true;
    return this.#held.length > 0;
  }

  get disposed() {
    return this.#disposed;
  }

  /**
   * Resolves with {positions, stats, distortion?}, or null when a newer
   * preview superseded it. `distortion`: a heat map kind to send back with
   * the positions (protocol.js, Request.deform). `iterations`: warm-started
   * iterations (the core caps a preview's at kPreviewIterations).
   */
  preview(op, distortion = null, iterations = LIVE_PREVIEW_ITERATIONS) {
    return new Promise((resolve, reject) => {
      this.#queuedPreview?.resolve(null);
      this.#queuedPreview = { op, distortion, iterations, resolve, reject };
      this.#sendQueuedPreview();
    });
  }

  /** Forgets a waiting preview (the gesture ended); the one in flight still answers. */
  dropQueuedPreview() {
    this.#queuedPreview?.resolve(null);
    this.#queuedPreview = null;
  }

  #sendQueuedPreview() {
    if (this.#previewInFlight || !this.#queuedPreview) return;
    const { op, distortion, iterations, resolve, reject } = this.#queuedPreview;
    this.#queuedPreview = null;
    // A preview runs `iterations` warm-started iterations; the committed
    // edit on release gets the iteration cap.
    const { maxIterations, ...previewOp } = op;
    previewOp.maxIterations = iterations;
    const id = this.#nextId;
    this.request(Request.deform, { op: { ...previewOp, preview: true }, commit: false, distortion }).then(resolve, reject);
    if (!this.#disposed) this.#previewInFlight = id;
  }
}

// Work of a disposed modeller, asked for before the dispose (queued, or
// under way) is stopped, not refused: 'cancelled', as a cancel() is. (An api
// call made after the dispose is refused before it gets here, create-api.js.)
function stoppedByDispose() {
  return new SolverError({ code: 'cancelled', message: 'stopped: this modeller was disposed' });
}
