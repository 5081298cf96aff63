// What one modeller holds outside its own objects: DOM listeners, timers and
// clean-up steps (a pending animation frame, a ResizeObserver, a Worker). dispose() undoes
// all of them, last first; `size` tells a test how many are still held.
export class Lifetime {
  #listeners = new Set();
  #cleanups = [];
  #disposed = false;

  /** addEventListener that dispose() removes; returns a function that removes it earlier. */
  listen(target, type, handler, options) {
    this.#assertAlive();
    const entry = { target, type, handler, options };
    target.addEventListener(type, handler, options);
    this.#listeners.add(entry);
    return () => {
      if (!this.#listeners.delete(entry)) return;
      target.removeEventListener(type, handler, options);
    };
  }

  /** setInterval that dispose() clears. */
  every(ms, callback) {
    const id = setInterval(callback, ms);
    this.defer(() => clearInterval(id));
    return id;
  }

  /** Runs `cleanup` at dispose(). */
  defer(cleanup) {
    this.#assertAlive();
    this.#cleanups.push(cleanup);
  }

  get disposed() {
    return this.#disposed;
  }

  /** DOM listeners still registered. */
  get listenerCount() {
    return this.#listeners.size;
  }

  /** Listeners and clean-up steps still held (0 after dispose). */
  get size() {
    return this.#listeners.size + this.#cleanups.length;
  }

  dispose() {
    if (this.#disposed) return;
    this.#disposed = true;
    for (const { target, type, handler, options } of this.#listeners) target.removeEventListener(type, handler, options);
    this.#listeners.clear();
    const failures = [];
    for (const cleanup of this.#cleanups.reverse()) {
      try {
        cleanup();
      } catch (error) {
        failures.push(error);
      }
    }
    this.#cleanups = [];
    if (failures.length > 0) throw new AggregateError(failures, 'anisoform: dispose did not finish cleanly');
  }

  #assertAlive() {
    if (this.#disposed) throw new Error('anisoform: this modeller was disposed');
  }
}
