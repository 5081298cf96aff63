// Runs the op stack's operations one at a time and puts the document's
// states in the solver worker: state n is the positions after the first n
// ops, taken from the snapshot cache when it has them, else replayed by the
// core from the nearest cached state (Session.replay), so that every state
// is bitwise what a replay of the document gives.
//
// Every operation runs after the previous one (run), and the worker handles
// requests in order, so the session's rest pose is always the state the page
// last put there.
import { Request } from '../worker/protocol.js';
import { SnapshotCache } from './snapshot-cache.js';
import { inPageWords } from '../editor/edit-wording.js';

export class OpRunner {
  #editor;
  #client;
  #document;
  #dropPattern;
  #chain = Promise.resolve();
  // The core's word on ops of this operation's replays that left the mesh
  // unchanged (an op's region selecting nothing after a change): said when
  // the state is shown.
  #unchanged = [];
  cache = new SnapshotCache();
  /** Bumped whenever the rest pose changes: a selection rule holds for one rest pose only. */
  restVersion = 0;
  /** The state on screen (show). */
  shown = 0;

  /** document: () => the EditDocument the states belong to. */
  constructor({ editor, client, document, dropPattern }) {
    this.#editor = editor;
    this.#client = client;
    this.#document = document;
    this.#dropPattern = dropPattern;
  }

  /** Runs `work` after every operation before it; busy from the call on (undo, redo and gestures wait). */
  run(work) {
    const done = this.#editor.beginBusy();
    const running = this.#chain.then(() => {
      this.#unchanged = [];
      return work();
    }).finally(done);
    this.#chain = running.catch(() => {});
    return running;
  }

  /**
   * The core's replay of ops [from, to) of `json` (default: the document)
   * from the worker's rest pose; `preview`: each op as a live preview;
   * `distortion`: the heat map's kind to send back (default: the one shown);
   * `label`: what its progress messages begin with.
   */
  replay(from, to, { json = this.#document().toJSON(), preview = false, distortion = this.#editor.heatMapKind, label } = {}) {
    // The core's replay leaves the session with no selection (replay_document):
    // the page's goes again before the next edit or flattening that uses it.
    this.#editor.selectionState.forget();
    return this.#client.request(Request.replay, { document: json, from, to, preview, distortion, label })
      .then((result) => {
        if (!preview) this.#unchanged.push(...(result.summary?.warnings ?? []));
        return result;
      });
  }

  /** Puts positions (a cached state) in the worker as its rest pose. */
  setPositions({ exact }) {
    const copy = exact.slice();
    return this.#client.request(Request.setPositions, { positions: copy }, [copy.buffer]);
  }

  /** Puts state n in the worker (its rest pose) and, unless show is false, on screen. */
  async restore(n, { show = true } = {}) {
    const cached = this.cache.get(n);
    if (cached) {
      await this.setPositions(cached);
      if (show) this.show(n, cached);
      return;
    }
    const from = this.cache.nearest(n);
    if (from > 0) await this.setPositions(this.cache.get(from));
    const result = await this.replay(from, n, { label: n - from > 1 ? `Edits ${from + 1}-${n}` : `Edit ${n}` });
    this.cache.set(n, { positions: result.positions, exact: result.exact });
    if (show) this.show(n, result);
  }

  /**
   * Puts the state on screen into a new worker (SolverClient.restart, after
   * a cancel): the mesh as loaded (state 0, kept exactly, so its hash is the
   * document's), then that state as the rest pose, replayed by the core from
   * the nearest cached state when it is no longer cached. `post` sends ahead
   * of every other request.
   */
  async seed(post) {
    const { triangles } = this.#editor.requireDocument();
    // The page draws and picks this mesh already: no normals or BVH back (display: false).
    await post(Request.setMesh, { positions: this.cache.get(0).exact.slice(), triangles: triangles.slice(), weld: false, display: false });
    const n = this.shown;
    const from = this.cache.nearest(n);
    if (from > 0) await post(Request.setPositions, { positions: this.cache.get(from).exact.slice() });
    if (from < n) await post(Request.replay, { document: this.#document().toJSON(), from, to: n, preview: false });
    this.restVersion++;
  }

  /**
   * Re-runs the document from op `index` on, op by op, so that every later
   * state is cached again for undo; resolves the last op's solve stats (null
   * when it is off, or when no op is left from `index` on). The new states
   * replace the cached ones only once all are solved: after a failure or a
   * cancel (the document's change taken back) the cache still holds the
   * states on screen, which come back at once instead of being replayed.
   */
  async rerunFrom(index) {
    const n = this.#document().ops.length;
    if (index >= n) {
      // No op from there on (the last one was deleted): its input is the result.
      this.cache.dropAfter(index);
      await this.restore(n);
      return null;
    }
    await this.restore(index, { show: false });
    const states = [];
    const label = (state) => `Edit ${state + 1} of ${n}`;
    for (let state = index; state < n - 1; state++) {
      const { positions, exact } = await this.replay(state, state + 1, { label: label(state) });
      states.push({ positions, exact });
    }
    const last = await this.replay(n - 1, n, { label: label(n - 1) });
    this.cache.dropAfter(index);
    states.forEach((state, k) => this.cache.set(index + 1 + k, state));
    this.show(n, last);
    return last.summary.last ?? null;
  }

  /** Shows state n (and caches it, given its exact positions): the mesh's positions are now those. */
  show(n, { positions, exact, distortion }) {
    if (exact) this.cache.set(n, { positions, exact });
    this.shown = n;
    this.restVersion++;
    this.#dropPattern();
    const mesh = this.#editor.requireDocument();
    mesh.positions = positions;
    this.#editor.emit('positions', { positions, live: false, distortion });
    this.#editor.emit('change', { reason: 'positions' });
    if (this.#unchanged.length === 0) return;
    const document = this.#document();
    const message = [...new Set(this.#unchanged)].map((text) => inPageWords(new Error(text), document).message).join(' ');
    this.#unchanged = [];
    this.#editor.emit('warning', { message, source: 'edit' });
  }
}
