// A minimal event emitter: the editor, the viewer and the public API announce
// what changed, and panels subscribe. `on` returns the unsubscribe function.
export class EventEmitter {
  #listeners = new Map();

  on(event, callback) {
    if (!this.#listeners.has(event)) this.#listeners.set(event, new Set());
    this.#listeners.get(event).add(callback);
    return () => this.#listeners.get(event)?.delete(callback);
  }

  /** Forgets every listener (a disposed modeller tells no one anything more). */
  clearListeners() {
    this.#listeners.clear();
  }

  emit(event, payload) {
    const listeners = this.#listeners.get(event);
    if (!listeners) return;
    for (const callback of [...listeners]) {
      try {
        callback(payload);
      } catch (error) {
        // A failing subscriber (an embedder's callback) must not break the editor.
        console.error(`anisoform: a '${event}' listener threw`, error);
      }
    }
  }
}
