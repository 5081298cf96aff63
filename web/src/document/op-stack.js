// The edit document as the page's source of truth: every committed edit is
// an op (resolved by the core: Session.resolveOp) appended to the document
// and solved by the core's replay of that one op, so that a later replay of
// the document (a fresh page, Node, the CLI) gives bitwise the same
// positions. Undo and redo move over the ops; toggling an op or changing its
// amounts re-runs it and the ops after it; snapshots of the states between
// ops are a cache (snapshot-cache.js). After every change the document and
// the mesh bytes are autosaved (autosave.js).
//
// Live re-parameterisation (a slider, setParameter with {preview: true}):
// on the LAST op, the worker's rest pose is put at that op's input and its
// region selected once; each slider value is then a warm-started
// one-iteration preview (no commit). On an earlier op, each value replays
// the ops from it on as previews, from its cached input (#previewReplay).
// The release (no preview) re-runs the document from the op, as a replay would.
//
// Every operation runs after the previous one (#run), and the worker handles
// requests in order, so the session's rest pose is always the state the page
// last put there.
import { Request } from '../worker/protocol.js';
import { foldOverWarning } from '../editor/edit-wording.js';
import { EditDocument, regionSteps } from './edit-document.js';
import { SnapshotCache } from './snapshot-cache.js';
import { Autosave } from './autosave.js';

const badParameter = (message) => Object.assign(new Error(message), { code: 'bad-parameter' });

export class OpStack {
  #editor;
  #client;
  #dropPattern;
  #cache = new SnapshotCache();
  #autosave = new Autosave();
  #chain = Promise.resolve();
  #live = null; // {opId, index, ready: Promise} (the last op), or {opId, index, replay: true}
  #waitingReplay = null; // the latest value of an earlier op's slider: {opId, index, op, resolve, reject}
  #replaying = false;
  #mesh = null; // {name, bytes}
  #restoring = false;
  /** @type {EditDocument|null} */
  document = null;
  /** Bumped whenever the rest pose changes: a selection rule holds for one rest pose only. */
  restVersion = 0;

  constructor({ editor, client, dropPattern }) {
    this.#editor = editor;
    this.#client = client;
    this.#dropPattern = dropPattern;
  }

  get snapshots() {
    return this.#cache;
  }

  /** A new mesh: an empty document whose state 0 is the mesh as loaded. */
  adoptMesh({ info, positions, exact, hash, sourceBytes }, name) {
    this.#live = null;
    this.#mesh = { name, bytes: sourceBytes };
    this.document = new EditDocument({ name, vertices: info.vertices, triangles: info.triangles, hash });
    this.#cache.clear();
    this.#cache.set(0, { positions, exact });
    this.restVersion++;
    // A new mesh is new work: it replaces the autosaved one (not while that is
    // being restored). The load's own 'change' {reason: 'load'} follows, so
    // the new document is announced without a 'change' of its own.
    if (this.#restoring) this.#emitDocument({ change: false });
    else this.#changed({ change: false });
  }

  /** The document as JSON (api.document()). */
  toJSON() {
    if (!this.document) throw badParameter('no mesh is loaded yet');
    return this.document.toJSON();
  }

  // ---- committing ----------------------------------------------------------

  /** Resolves `solverOp` on the current selection, appends it and solves it; resolves with its stats. */
  commit(solverOp, label) {
    return this.#run(async () => {
      const editor = this.#editor;
      const mesh = editor.requireDocument();
      const steps = regionSteps(editor.selectionState.ruleFor(this.restVersion), mesh.selection, mesh.selectionCount);
      editor.selectionState.syncForEdit();
      const { op } = await this.#client.request(Request.resolveOp, { op: solverOp });
      const index = this.document.ops.length;
      const undone = [...this.document.undone];
      const entry = this.document.append({ label, steps, op });
      let result;
      try {
        result = await this.#replay(index, index + 1);
      } catch (error) {
        this.document.dropLast(entry);
        this.document.undone = undone;
        throw error;
      }
      this.#cache.dropAfter(index);
      this.#show(index + 1, result);
      editor.history.push({ label, undo: () => this.#undoOp(), redo: () => this.#redoOp() });
      const stats = result.summary.last;
      if (stats?.inverted > 0) editor.emit('warning', { message: foldOverWarning(stats.inverted) });
      this.#changed();
      return stats;
    });
  }

  #undoOp() {
    this.#step(() => this.document.undoLast(), 'Undo failed');
  }

  #redoOp() {
    this.#step(() => this.document.redoNext(), 'Redo failed');
  }

  // Undo, redo and reset run while nothing else does (editor.undo() refuses
  // while busy): a cached state is shown at once, as the history promises;
  // otherwise it is replayed.
  #step(change, context) {
    if (!change()) return;
    this.#live = null;
    this.#dropWaitingPreviews();
    const n = this.document.ops.length;
    const cached = this.#cache.get(n);
    if (cached) {
      const exact = cached.exact.slice();
      this.#client.request(Request.setPositions, { positions: exact }, [exact.buffer])
        .catch((error) => this.#editor.report(error, 'The solver could not restore the positions'));
      this.#show(n, cached);
      this.#changed();
      return;
    }
    this.#run(async () => {
      await this.#restore(n);
      this.#changed();
    }).catch((error) => this.#editor.report(error, context));
  }

  /** Back to the mesh as loaded: the ops are cleared (undoable) and so is the autosave. */
  reset() {
    const document = this.document;
    if (!document || document.ops.length === 0) return false;
    const cleared = { ops: document.ops, undone: document.undone };
    const clear = () => {
      this.#step(() => {
        document.ops = [];
        document.undone = [];
        return true;
      }, 'Reset failed');
      this.#autosave.clear().catch((error) => this.#editor.report(error, 'Autosave'));
    };
    clear();
    this.#editor.history.push({
      label: 'Reset to loaded mesh',
      undo: () => this.#step(() => {
        document.ops = cleared.ops;
        document.undone = cleared.undone;
        return true;
      }, 'Undo failed'),
      redo: clear,
    });
    return true;
  }

  // ---- the op list: toggle, amounts, parameters ----------------------------

  setEnabled(opId, enabled) {
    if (typeof enabled !== 'boolean') return Promise.reject(badParameter('setOpEnabled needs true or false'));
    return this.#run(async () => {
      const index = this.#requireDocument().indexOf(opId);
      const entry = this.document.ops[index];
      const before = entry.enabled;
      entry.enabled = enabled;
      try {
        await this.#rerunFrom(index);
      } catch (error) {
        entry.enabled = before;
        await this.#restore(this.document.ops.length).catch(() => {});
        throw error;
      }
      this.#changed();
    });
  }

  /**
   * Changes op `opId`'s transform ({transform: {...}} merged into it) and
   * re-runs it and the ops after it. With {preview: true} on the last op: a
   * live preview only (a slider being dragged); call again without it to commit.
   */
  setParameter(opId, patch, { preview = false } = {}) {
    if (!patch || typeof patch !== 'object' || Object.keys(patch).some((key) => key !== 'transform')
        || typeof patch.transform !== 'object' || patch.transform === null) {
      return Promise.reject(badParameter("setParameter(opId, {transform: {...}}): only 'transform' can be set"));
    }
    let index;
    let op;
    const document = this.document;
    try {
      index = this.#requireDocument().indexOf(opId);
      op = document.withTransform(opId, patch.transform);
    } catch (error) {
      return Promise.reject(error);
    }
    if (preview && document.ops[index].enabled) {
      return index === document.ops.length - 1 ? this.#preview(opId, index, op) : this.#previewReplay(opId, index, op);
    }
    return this.#run(async () => {
      const entry = this.document.ops[this.document.indexOf(opId)];
      const before = entry.op;
      entry.op = op;
      try {
        await this.#rerunFrom(index);
      } catch (error) {
        entry.op = before;
        await this.#restore(this.document.ops.length).catch(() => {});
        throw error;
      }
      this.#changed();
    });
  }

  async #preview(opId, index, op) {
    if (this.#live?.opId !== opId) {
      const live = { opId, index };
      this.#live = live;
      live.ready = this.#run(async () => {
        await this.#restore(index, { show: false });
        await this.#client.request(Request.selectDocumentRegion, { document: this.document.toJSON(), opId });
        this.#editor.selectionState.forget();
      }, { keepLive: true });
    }
    const live = this.#live;
    await live.ready;
    // One warm-started iteration per slider value: each frame refines the
    // last shape towards the new amount, so the shape follows the slider at
    // the solver's iteration rate; the release solves in full.
    const result = await this.#client.preview({ ...op, warmStart: true }, this.#editor.heatMapKind, { iterations: 1 });
    if (!result || this.#live !== live) return null;
    this.#editor.emit('positions', { positions: result.positions, live: true, distortion: result.distortion });
    this.#editor.emit('stats', { ...result.stats, live: true });
    return { iterations: result.stats.iterations, ms: result.stats.ms };
  }

  // A slider on an earlier op: the ops from it on are replayed from its input
  // (cached) with the new amounts, each as a cold live preview (the core's
  // replay option `preview`: a few iterations), without touching the
  // document or the cache; the release commits the full replay. Only the
  // latest value waits while one replays.
  #previewReplay(opId, index, op) {
    this.#waitingReplay?.resolve(null);
    return new Promise((resolve, reject) => {
      this.#waitingReplay = { opId, index, op, resolve, reject };
      if (!this.#replaying) this.#replayWaiting();
    });
  }

  async #replayWaiting() {
    this.#replaying = true;
    while (this.#waitingReplay) {
      const { opId, index, op, resolve, reject } = this.#waitingReplay;
      this.#waitingReplay = null;
      await this.#run(async () => {
        this.#live = { opId, index, replay: true };
        await this.#restore(index, { show: false });
        const json = this.document.toJSON();
        json.ops[index].op = op;
        return this.#client.request(Request.replay, { document: json, from: index, to: json.ops.length,
          preview: true, distortion: this.#editor.heatMapKind });
      }, { keepLive: this.#live?.opId === opId }).then((result) => {
        if (this.#live?.opId !== opId) return resolve(null);
        this.#editor.emit('positions', { positions: result.positions, live: true, distortion: result.distortion });
        resolve({ replayed: result.summary.replayed });
      }, reject);
    }
    this.#replaying = false;
  }

  // ---- an op's region ------------------------------------------------------

  /** The weights of op `opId`'s region on its input (where the op evaluates it), to show them. */
  regionWeights(opId) {
    return this.#run(async () => {
      const index = this.#requireDocument().indexOf(opId);
      await this.#restore(index, { show: false });
      const { weights } = await this.#client.request(Request.selectDocumentRegion,
        { document: this.document.toJSON(), opId });
      this.#editor.selectionState.forget();
      await this.#restore(this.document.ops.length, { show: false });
      return weights;
    });
  }

  /** The current selection (its rule, else its weights) becomes op `opId`'s region; it and the later ops re-run. */
  useSelectionAsRegion(opId) {
    return this.#run(async () => {
      const index = this.#requireDocument().indexOf(opId);
      const mesh = this.#editor.requireDocument();
      const steps = regionSteps(this.#editor.selectionState.ruleFor(this.restVersion), mesh.selection, mesh.selectionCount);
      const entry = this.document.ops[index];
      const before = entry.region;
      entry.region = this.document.regionFor(steps);
      try {
        await this.#rerunFrom(index);
      } catch (error) {
        entry.region = before;
        await this.#restore(this.document.ops.length).catch(() => {});
        throw error;
      }
      this.#changed();
    });
  }

  // ---- opening and autosave ------------------------------------------------

  /** Replays `json` on the current mesh, or on `meshBytes` (named json.mesh.name); on failure the current work stays. */
  open(json, meshBytes) {
    const editor = this.#editor;
    return this.#run(async () => {
      if (!json || typeof json !== 'object') throw badParameter('open() needs an edit document object');
      const previous = this.document && { json: this.document.toJSON(), mesh: this.#mesh };
      if (meshBytes !== undefined) await editor.load(meshBytes, json.mesh?.name);
      else this.#requireDocument();
      let result;
      try {
        result = await this.#client.request(Request.replay, { document: json, from: 0, to: json.ops?.length ?? 0,
          distortion: editor.heatMapKind });
      } catch (error) {
        // The core's replay leaves the session as it was; only a mesh loaded for it is undone.
        if (meshBytes !== undefined && previous) await this.#reopen(previous);
        throw error;
      }
      this.#adoptDocument(json, result);
    });
  }

  async #reopen({ json, mesh }) {
    await this.#editor.load(mesh.bytes, mesh.name);
    this.#adoptDocument(json, await this.#client.request(Request.replay, { document: json, from: 0, to: json.ops.length }));
  }

  #adoptDocument(json, result) {
    const state0 = this.#cache.get(0);
    this.document = EditDocument.fromJSON(json);
    this.#cache.clear();
    this.#cache.set(0, state0);
    this.#show(this.document.ops.length, result);
    const history = this.#editor.history;
    history.clear();
    for (const entry of this.document.ops) {
      history.push({ label: entry.label, undo: () => this.#undoOp(), redo: () => this.#redoOp() });
    }
    this.#changed();
  }

  /** From now on the work is autosaved (the standalone site; createModeller's `autosave`). */
  enableAutosave() {
    this.#autosave.enabled = true;
  }

  /** Restores the autosaved work, if any; resolves true when a saved mesh was loaded. */
  async restoreAutosave() {
    const record = await this.#autosave.load().catch((error) => {
      this.#editor.report(error, 'Autosave');
      return null;
    });
    if (!record) return false;
    this.#restoring = true;
    try {
      await this.#editor.load(record.meshBytes, record.meshName);
    } finally {
      this.#restoring = false;
    }
    await this.open(record.document).catch((error) => this.#editor.report(error, 'The saved work could not be replayed'));
    return true;
  }

  clearAutosave() {
    return this.#autosave.clear();
  }

  // ---- helpers -------------------------------------------------------------

  #requireDocument() {
    if (!this.document) throw badParameter('no mesh is loaded yet');
    return this.document;
  }

  // One operation at a time; a live preview is left before anything else.
  // Busy from the call on: undo, redo and gestures wait for it.
  #run(work, { keepLive = false } = {}) {
    const done = this.#editor.beginBusy();
    const leavingLive = this.#live !== null && !keepLive;
    if (leavingLive) this.#live = null;
    if (!keepLive) this.#dropWaitingPreviews();
    const running = this.#chain.then(async () => {
      if (leavingLive) await this.#restore(this.document.ops.length, { show: false });
      return work();
    }).finally(done);
    this.#chain = running.catch(() => {});
    return running;
  }

  // A change (or a commit) supersedes the slider values not solved yet.
  #dropWaitingPreviews() {
    this.#client.dropQueuedPreview();
    this.#waitingReplay?.resolve(null);
    this.#waitingReplay = null;
  }

  #replay(from, to) {
    return this.#client.request(Request.replay, { document: this.document.toJSON(), from, to,
      distortion: this.#editor.heatMapKind });
  }

  // Puts state n in the worker (its rest pose) and, unless show is false, on screen.
  async #restore(n, { show = true } = {}) {
    const cached = this.#cache.get(n);
    if (cached) {
      const exact = cached.exact.slice();
      await this.#client.request(Request.setPositions, { positions: exact }, [exact.buffer]);
      if (show) this.#show(n, cached);
      return;
    }
    const from = this.#cache.nearest(n);
    if (from > 0) {
      const exact = this.#cache.get(from).exact.slice();
      await this.#client.request(Request.setPositions, { positions: exact }, [exact.buffer]);
    }
    const result = await this.#replay(from, n);
    this.#cache.set(n, { positions: result.positions, exact: result.exact });
    if (show) this.#show(n, result);
  }

  // Op by op, so that every state after `index` is cached again for undo.
  async #rerunFrom(index) {
    this.#cache.dropAfter(index);
    await this.#restore(index, { show: false });
    const n = this.document.ops.length;
    for (let state = index; state < n - 1; state++) {
      const { positions, exact } = await this.#replay(state, state + 1);
      this.#cache.set(state + 1, { positions, exact });
    }
    this.#show(n, await this.#replay(n - 1, n));
  }

  #show(n, { positions, exact, distortion }) {
    if (exact) this.#cache.set(n, { positions, exact });
    this.restVersion++;
    this.#dropPattern();
    const mesh = this.#editor.requireDocument();
    mesh.positions = positions;
    this.#editor.emit('positions', { positions, live: false, distortion });
    this.#editor.emit('change', { reason: 'positions' });
  }

  #emitDocument({ change = true } = {}) {
    this.#editor.emit('document', this.document);
    if (change) this.#editor.emit('change', { reason: 'document' });
  }

  #changed({ change = true } = {}) {
    this.#emitDocument({ change });
    const { name, bytes } = this.#mesh;
    this.#autosave.save({ document: this.document.toJSON(), meshName: name, meshBytes: bytes })
      .catch((error) => this.#editor.report(error, 'Autosave'));
  }
}
