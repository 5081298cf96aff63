// The page's side of the solver worker: promises per request, progress
// events, and coalescing of live previews.
//
// Coalescing: at most one preview is in flight and at most one waits. A newer
// preview replaces the waiting one (whose promise resolves with null), so
// while the pointer moves faster than the solver, the worker only ever solves
// the latest position, never a backlog of stale ones.
import { EventEmitter } from '../shared/event-emitter.js';
import { PROGRESS, Request } from './protocol.js';

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
  #disposed = false;

  /**
   * workerUrl / wasmUrl: where the solver worker and its WASM are, when not
   * beside this module (a bundler that moves files, a CDN copy of the WASM;
   * the worker must be same-origin). The default `new URL(..., import.meta.url)`
   * stays literal so bundlers find and emit both files.
   */
  constructor({ workerUrl, wasmUrl } = {}) {
    super();
    this.#wasmUrl = wasmUrl === undefined ? undefined : String(wasmUrl);
    this.#worker = workerUrl === undefined
      ? new Worker(new URL('./solver-worker.js', import.meta.url), { type: 'module' })
      : new Worker(workerUrl, { type: 'module' });
    this.#worker.onmessage = (event) => this.#receive(event.data);
    this.#worker.onerror = (event) => {
      const failure = new SolverError({
        code: 'internal',
        message: `The solver stopped: ${event.message || 'the worker could not start'}`,
      });
      for (const { reject } of this.#pending.values()) reject(failure);
      this.#pending.clear();
      this.#previewInFlight = 0;
      this.#sendQueuedPreview();
    };
  }

  #receive(message) {
    if (message.kind === PROGRESS) {
      this.emit('progress', { stage: message.stage, message: message.message });
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
    if (message.ok) pending.resolve(message.result);
    else pending.reject(new SolverError(message.error));
  }

  request(kind, payload = {}, transfer = []) {
    if (this.#disposed) return Promise.reject(disposedError());
    // The WASM location travels with init, the one request that loads it.
    if (kind === Request.init && this.#wasmUrl !== undefined) payload = { ...payload, wasmUrl: this.#wasmUrl };
    const id = this.#nextId++;
    return new Promise((resolve, reject) => {
      this.#pending.set(id, { resolve, reject });
      this.#worker.postMessage({ id, kind, ...payload }, transfer);
    });
  }

  /**
   * Ends the worker, and with it the WASM session and its memory; requests
   * still waiting reject.
   */
  dispose() {
    if (this.#disposed) return;
    this.#disposed = true;
    this.#worker.terminate();
    this.#queuedPreview?.resolve(null);
    this.#queuedPreview = null;
    for (const { reject } of this.#pending.values()) reject(disposedError());
    this.#pending.clear();
  }

  /** True while a request is waiting for the worker. */
  get busy() {
    return this.#pending.size > 0;
  }

  /**
   * Resolves with {positions, stats, distortion?}, or null when a newer
   * preview superseded it. `distortion`: a heat map kind to send back with
   * the positions (protocol.js, Request.deform).
   */
  preview(op, distortion = null, { iterations } = {}) {
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
    // A preview runs the solver's few warm-started iterations (or `iterations`,
    // fewer still); the committed edit on release gets the iteration cap.
    const { maxIterations, ...previewOp } = op;
    if (iterations) previewOp.maxIterations = iterations;
    const id = this.#nextId;
    this.request(Request.deform, { op: { ...previewOp, preview: true }, commit: false, distortion }).then(resolve, reject);
    if (!this.#disposed) this.#previewInFlight = id;
  }
}

function disposedError() {
  return new SolverError({ code: 'bad-parameter', message: 'this modeller was disposed' });
}
