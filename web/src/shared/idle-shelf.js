// Things a disposed modeller hands to the next one (its solver worker, its 3D
// view's WebGL renderer): each kept idle under a key for a while, then ended.
// The shelf holds at most `keep` of them, ending the oldest beyond that, each
// for at most `idleMs`; close() ends them, and what is put back later.
export class IdleShelf {
  /** Idle entries, oldest first: {item, key, timer}. */
  #entries = [];
  #keep;
  #idleMs;
  #end;
  #onKept;
  #onTaken;
  #closed = false;

  /**
   * @param {object} options
   *   keep: how many items to keep (0 keeps none)
   *   idleMs: how long an item is kept
   *   end(item): ends an item for good
   *   onKept(item, drop): called as an item is kept; drop() ends it early (an item that fails while idle)
   *   onTaken(item): called as an item leaves the shelf (taken or ended), to undo onKept
   */
  constructor({ keep, idleMs, end, onKept = () => {}, onTaken = () => {} }) {
    this.#keep = keep;
    this.#idleMs = idleMs;
    this.#end = end;
    this.#onKept = onKept;
    this.#onTaken = onTaken;
  }

  /** An idle item kept under `key`, taken off the shelf; null if there is none. */
  take(key) {
    const index = this.#entries.findIndex((entry) => entry.key === key);
    if (index < 0) return null;
    const [entry] = this.#entries.splice(index, 1);
    clearTimeout(entry.timer);
    this.#onTaken(entry.item);
    return entry.item;
  }

  /** Keeps an idle item under `key`; ends it at once if the shelf keeps none or is closed. */
  put(item, key) {
    if (this.#closed || this.#keep === 0) {
      this.#end(item);
      return;
    }
    if (this.#entries.length >= this.#keep) this.#drop(this.#entries[0]);
    const entry = { item, key, timer: 0 };
    entry.timer = setTimeout(() => this.#drop(entry), this.#idleMs);
    this.#entries.push(entry);
    this.#onKept(item, () => this.#drop(entry));
  }

  #drop(entry) {
    const index = this.#entries.indexOf(entry);
    if (index < 0) return; // taken or ended already
    this.#entries.splice(index, 1);
    clearTimeout(entry.timer);
    this.#onTaken(entry.item);
    this.#end(entry.item);
  }

  /** The number of items kept. */
  get size() {
    return this.#entries.length;
  }

  /** Ends the items kept; items put back later are ended at once. */
  close() {
    this.#closed = true;
    for (const entry of [...this.#entries]) this.#drop(entry);
  }
}
