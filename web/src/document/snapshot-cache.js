// Positions after the first n ops of the edit document ("state n"), kept so
// that undo, redo and a re-run from an op need not replay from the mesh as
// loaded. A cache, never the truth (the document is): entries are dropped,
// least recently used first, to stay within a memory budget in bytes; state 0
// (the mesh as loaded) is always kept. Each entry holds the float32 positions
// to draw and the session's doubles (`exact`), so that restoring one gives
// bitwise the state a replay would.
export const DEFAULT_SNAPSHOT_BUDGET = 64 * 1024 * 1024;

const bytesOf = ({ positions, exact }) => positions.byteLength + exact.byteLength;

export class SnapshotCache {
  #budget;
  #entries = new Map(); // state -> {positions, exact}; Map order = least recently used first
  #bytes = 0;

  constructor(budgetBytes = DEFAULT_SNAPSHOT_BUDGET) {
    this.#budget = budgetBytes;
  }

  get bytes() {
    return this.#bytes;
  }

  get budget() {
    return this.#budget;
  }

  set budget(bytes) {
    this.#budget = bytes;
    this.#evict();
  }

  clear() {
    this.#entries.clear();
    this.#bytes = 0;
  }

  set(state, snapshot) {
    this.delete(state);
    this.#entries.set(state, snapshot);
    this.#bytes += bytesOf(snapshot);
    this.#evict();
  }

  get(state) {
    const snapshot = this.#entries.get(state);
    if (!snapshot) return null;
    this.#entries.delete(state);
    this.#entries.set(state, snapshot);
    return snapshot;
  }

  delete(state) {
    const snapshot = this.#entries.get(state);
    if (!snapshot) return;
    this.#entries.delete(state);
    this.#bytes -= bytesOf(snapshot);
  }

  /** Drops every state after `state` (an op at index >= state changed). */
  dropAfter(state) {
    for (const key of [...this.#entries.keys()]) if (key > state) this.delete(key);
  }

  /** The highest cached state <= `state` (state 0 is always there). */
  nearest(state) {
    let best = 0;
    for (const key of this.#entries.keys()) if (key <= state && key > best) best = key;
    return best;
  }

  #evict() {
    for (const key of [...this.#entries.keys()]) {
      if (this.#bytes <= this.#budget) return;
      if (key !== 0) this.delete(key);
    }
  }
}
