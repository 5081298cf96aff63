// The edit document as the page's source of truth: every committed edit is
// an op (resolved by the core: Session.resolveOp) appended to the document
// and solved by the core's replay of that one op, so that a later replay of
// the document (a fresh page, Node, the CLI) gives bitwise the same
// positions. Undo and redo move over the ops; toggling an op, changing its
// amounts or its region re-runs it and the ops after it. The parts:
//   op-runner.js             one operation at a time; the states between ops (a cache) in the worker
//   live-preview.js          a slider being dragged (setParameter with {preview: true})
//   document-persistence.js  open(), the 'document' announcements, autosave
import { Request } from '../worker/protocol.js';
import { describeEdit, foldOverWarning, inPageWords } from '../editor/edit-wording.js';
import { EditDocument, regionSteps } from './edit-document.js';
import { OpRunner } from './op-runner.js';
import { LivePreview } from './live-preview.js';
import { DocumentPersistence } from './document-persistence.js';
import { badParameter, cancelledError, editOfReplacedMeshError, gestureInProgressError } from '../shared/errors.js';

// An op's name is a list label, not a document: long enough for "Stretch the left sleeve, 2nd try".
const MAX_NAME_LENGTH = 80;
// What setParameter may change, in the words of its history step.
const PATCH_WORDS = { transform: 'amounts', method: 'method', direction: 'direction', move: 'move' };

// Why `patch` is no setParameter patch (null if it is one): an object with
// some of transform (an object), method (a string), direction (an object),
// move (an ARAP drag's [x, y, z]; the core checks the values).
function patchProblem(patch) {
  if (!patch || typeof patch !== 'object' || Array.isArray(patch)) return 'the patch must be an object';
  const keys = Object.keys(patch);
  if (keys.length === 0) return 'the patch changes nothing';
  const unknown = keys.find((key) => !(key in PATCH_WORDS));
  if (unknown) return `'${unknown}' cannot be set`;
  for (const key of ['transform', 'direction']) {
    if (key in patch && (typeof patch[key] !== 'object' || patch[key] === null || Array.isArray(patch[key]))) {
      return `${key} must be an object`;
    }
  }
  if ('method' in patch && typeof patch.method !== 'string') return 'method must be a string';
  if ('move' in patch && !Array.isArray(patch.move)) return 'move must be [x, y, z]';
  if (patch.direction?.type === 'screen') {
    return "a screen drag cannot be stored in an op: give its 3D vector, {type: 'global', vector}";
  }
  return null;
}

// Why setParameter's `patch` cannot change op `op` (null if it can): an
// ARAP drag (a move of handles) and a local transform are different edits;
// method switches among the transform methods only (it was taken, and the
// stretch silently became an ARAP drag of nothing).
function kindProblem(op, patch) {
  const drag = (op.method ?? 'anarap') === 'arap';
  if ('method' in patch && (patch.method === 'arap') !== drag) {
    return drag
      ? "this op is an ARAP drag: its method stays 'arap' (make a new edit for a local transform)"
      : "method 'arap' is an ARAP drag, not a method of this op's transform: choose 'anarap', 'andefgrad' or 'linear'";
  }
  if (drag && 'transform' in patch) return 'an ARAP drag has no transform: set its move';
  if (!drag && 'move' in patch) return `move is an ARAP drag's; this op is ${op.method ?? 'anarap'}: set its transform`;
  return null;
}

export class OpStack {
  #editor;
  #client;
  #runner;
  #live;
  #persistence;
  /** @type {EditDocument|null} */
  document = null;
  // The document as it was before a change still being solved (a commit's
  // new op, a re-run's new value): what toJSON() gives meanwhile.
  #settled = null;

  constructor({ editor, client, dropPattern }) {
    this.#editor = editor;
    this.#client = client;
    const document = () => this.document;
    const run = (work, options) => this.#run(work, options);
    this.#runner = new OpRunner({ editor, client, document, dropPattern });
    this.#live = new LivePreview({ editor, client, runner: this.#runner, run, document });
    this.#persistence = new DocumentPersistence({ editor, stack: this, runner: this.#runner, run,
      rebuildHistory: () => this.#rebuildHistory(), reportSolved: (stats) => this.#reportSolved(stats) });
  }

  /** Whether a slider's live preview holds the worker's state (live-preview.js). */
  get live() {
    return this.#live.active;
  }

  get snapshots() {
    return this.#runner.cache;
  }

  /** Bumped whenever the rest pose changes: a selection rule holds for one rest pose only. */
  get restVersion() {
    return this.#runner.restVersion;
  }

  /** A new mesh: an empty document whose state 0 is the mesh as loaded. */
  adoptMesh({ info, positions, exact, hash, sourceBytes }, name) {
    this.#live.leave();
    this.#persistence.mesh = { name, bytes: sourceBytes };
    this.document = new EditDocument({ name, vertices: info.vertices, triangles: info.triangles, hash });
    this.#runner.cache.clear();
    this.#runner.cache.set(0, { positions, exact });
    this.#runner.restVersion++;
    // A new mesh is new work: it replaces the autosaved one (not while that is
    // being restored). The load's own 'change' {reason: 'load'} follows, so
    // the new document is announced without a 'change' of its own.
    if (this.#persistence.restoring) this.#persistence.announce({ change: false });
    else this.#persistence.changed({ change: false });
  }

  /**
   * A cancel ended the worker mid-solve: `restart(seed)` gets a new one with
   * the state on screen (the cancelled work rejects with 'cancelled' and
   * leaves the document as it was); a live preview's state is gone with it.
   */
  restartSolver(restart) {
    this.#live.leave();
    return restart((post) => this.#runner.seed(post));
  }

  /**
   * The document as JSON (api.document()): the ops done so far. An op being
   * committed, or a change being re-run, is in it once solved: a cancel or a
   * failure leaves the document as it was.
   */
  toJSON() {
    return this.#settled ?? this.#requireDocument().toJSON();
  }

  // Runs work(), which changes the document and solves the change, with
  // toJSON() giving the document before the change until it settles.
  async #solving(work) {
    this.#settled = this.document.toJSON();
    try {
      return await work();
    } finally {
      this.#settled = null;
    }
  }

  // ---- committing, undo, redo, reset ---------------------------------------

  /** Resolves `solverOp` on the current selection, appends it and solves it; resolves with its stats. */
  commit(solverOp, label) {
    const editor = this.#editor;
    // A cancel() from here on stops it, even before its requests reach the
    // worker (the restarted worker would have solved and committed it).
    const cancels = editor.cancels;
    const mesh = editor.document;
    const stillWanted = () => {
      if (editor.cancels !== cancels) throw cancelledError();
      if (editor.document !== mesh) throw editOfReplacedMeshError();
    };
    // The selection of the call, not of when the edit runs (queued behind others).
    let steps, selection;
    try {
      steps = this.#selectionSteps();
      selection = editor.selectionState.snapshotForEdit();
    } catch (error) {
      return Promise.reject(error);
    }
    // A load may also arrive while the edit runs (it does not wait for the
    // edits): the worker then holds the new mesh, and what failed there or
    // was solved on the old one is not this edit's outcome.
    const onThisMesh = (error) => {
      if (editor.document !== mesh) throw editOfReplacedMeshError();
      throw error;
    };
    return this.#run(async () => {
      stillWanted();
      editor.selectionState.syncForEdit(selection);
      const { op } = await this.#client.request(Request.resolveOp, { op: solverOp }).catch((error) => {
        onThisMesh(inPageWords(error, this.document, { labelled: false }));
      });
      stillWanted();
      const index = this.document.ops.length;
      const undone = [...this.document.undone];
      const result = await this.#solving(async () => {
        const entry = this.document.append({ label, steps, op });
        try {
          return await this.#runner.replay(index, index + 1);
        } catch (error) {
          const worded = inPageWords(error, this.document, { labelled: false });
          this.document.dropLast(entry);
          this.document.undone = undone;
          return onThisMesh(worded);
        }
      });
      stillWanted();
      this.#runner.cache.dropAfter(index);
      this.#runner.show(index + 1, result);
      // The committed shape is the worker's new rest pose: it is factorized
      // in the background, not in the next edit's first preview.
      editor.prepareSolverSoon();
      editor.history.push(this.#historyEntry(label));
      const stats = result.summary.last;
      this.#reportSolved(stats);
      this.#persistence.changed();
      return stats;
    });
  }

  #historyEntry(label) {
    return {
      label,
      undo: () => this.#step(() => this.document.undoLast(), 'Undo failed'),
      redo: () => this.#step(() => this.document.redoNext(), 'Redo failed'),
    };
  }

  // The history of an opened document (saved edits, or the autosave after a
  // reload): each op committed in turn, then each op that is off turned off,
  // so that undo first turns those back on, then takes the ops away, as the
  // session that made them would have.
  #rebuildHistory() {
    const history = this.#editor.history;
    history.clear();
    for (const entry of this.document.ops) history.push(this.#historyEntry(entry.label));
    for (const { id, label, enabled } of this.document.ops) {
      if (enabled) continue;
      this.#pushStep(`Turn off ${label || id}`, () => this.#setOpField(id, 'enabled', true),
        () => this.#setOpField(id, 'enabled', false));
    }
  }

  // Undo, redo and reset run while nothing else does (editor.undo() refuses
  // while busy): a cached state is shown at once, as the history promises;
  // otherwise it is replayed. Either way the shape is the worker's new rest
  // pose, prepared in the background as after a commit (free when the
  // worker kept its factorization: the pose just left, below half the
  // vertex limit).
  #step(change, context) {
    if (!change()) return;
    this.#live.leave();
    const n = this.document.ops.length;
    const cached = this.#runner.cache.get(n);
    if (cached) {
      this.#runner.setPositions(cached)
        .catch((error) => this.#editor.report(error, 'The solver could not restore the positions'));
      this.#runner.show(n, cached);
      this.#persistence.changed();
      this.#editor.prepareSolverSoon();
      return;
    }
    this.#run(async () => {
      await this.#runner.restore(n);
      this.#persistence.changed();
      this.#editor.prepareSolverSoon();
    }).catch((error) => this.#editor.report(error, context));
  }

  /** Back to the mesh as loaded: the ops are cleared (undoable); the autosave keeps the mesh, without them. */
  reset() {
    const document = this.document;
    if (!document || document.ops.length === 0) return false;
    const cleared = { ops: document.ops, undone: document.undone };
    // The step autosaves the document, now empty, with the mesh (clearing
    // the autosave brought the default mesh back at the next reload).
    const clear = () => {
      this.#step(() => {
        document.ops = [];
        document.undone = [];
        return true;
      }, 'Reset failed');
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

  // ---- an op's switch, amounts and region ----------------------------------
  // Each change is a step of the history (undo and redo re-run the op and
  // the later ones with the value before or after), as a commit is.

  setEnabled(opId, enabled) {
    if (typeof enabled !== 'boolean') return Promise.reject(badParameter('setOpEnabled needs true or false'));
    if (this.#editor.gestureActive) return this.#refusedDuringGesture();
    return this.#changeOp(opId, 'enabled', enabled, (label) => `Turn ${enabled ? 'on' : 'off'} ${label}`);
  }

  /**
   * Changes op `opId` by `patch` ({transform} merged into its transform,
   * {method}, {direction} and {move} replacing its own; the core checks the values
   * as it re-runs) and re-runs it and the ops after it. With {preview: true}:
   * a live preview only (a slider being dragged, live-preview.js); call
   * again without it to commit.
   */
  setParameter(opId, patch, { preview = false } = {}) {
    if (this.#editor.gestureActive) return this.#refusedDuringGesture();
    const problem = patchProblem(patch);
    if (problem) return Promise.reject(badParameter(`setParameter(opId, {transform?, method?, direction?, move?}): ${problem}`));
    let index;
    let op;
    try {
      index = this.#requireDocument().indexOf(opId);
      op = this.document.withChanges(opId, patch);
    } catch (error) {
      return Promise.reject(error);
    }
    const kind = kindProblem(this.document.ops[index].op, patch);
    if (kind) return Promise.reject(badParameter(`setParameter(opId, patch): ${kind}`));
    if (preview && this.document.ops[index].enabled) return this.#live.preview(opId, index, op);
    const what = Object.keys(patch).map((key) => PATCH_WORDS[key]).join(' and ');
    return this.#changeOp(opId, 'op', op, (label) => `Change the ${what} of ${label}`);
  }

  /**
   * Drops a preview of setParameter not committed (a value typed, then
   * abandoned): the document's state shows again. False when none is shown.
   */
  dropPreview() {
    if (!this.#live.leave()) return false;
    this.#runner.run(() => this.#runner.restore(this.document.ops.length))
      .catch((error) => this.#editor.report(error, 'The preview was not dropped'));
    return true;
  }

  /** The weights of op `opId`'s region on its input (where the op evaluates it), to show them. */
  regionWeights(opId) {
    return this.#run(async () => {
      const index = this.#requireDocument().indexOf(opId);
      await this.#runner.restore(index, { show: false });
      const { weights } = await this.#client.request(Request.selectDocumentRegion,
        { document: this.document.toJSON(), opId });
      this.#editor.selectionState.forget();
      await this.#runner.restore(this.document.ops.length, { show: false });
      return weights;
    });
  }

  /** The current selection (its rule, else its weights) becomes op `opId`'s region; it and the later ops re-run. */
  useSelectionAsRegion(opId) {
    let steps;
    try {
      steps = this.#selectionSteps();
    } catch (error) {
      return Promise.reject(error);
    }
    return this.setRegion(opId, steps);
  }

  /** Op `opId`'s region becomes the one of these select steps ({region, falloff?, mode?}...); it and the later ops re-run. */
  setRegion(opId, steps) {
    if (this.#editor.gestureActive) return this.#refusedDuringGesture();
    if (!Array.isArray(steps) || steps.length === 0 || steps.some((step) => typeof step?.region !== 'object' || step.region === null)) {
      return Promise.reject(badParameter('setRegion(opId, steps): steps must be a list of select steps, each {region, falloff?, mode?}'));
    }
    let region;
    try {
      this.#requireDocument().indexOf(opId);
      region = this.document.regionFor(steps);
    } catch (error) {
      return Promise.reject(error);
    }
    return this.#changeOp(opId, 'region', region, (label) => `Change the region of ${label}`);
  }

  /** The select steps of op `opId`'s region (a copy). */
  stepsOfRegion(opId) {
    const { region } = this.#requireDocument().ops[this.document.indexOf(opId)];
    return structuredClone(this.document.regions.find((entry) => entry.name === region)?.steps ?? []);
  }

  /**
   * Names op `opId` (the Edits list's label, kept in saved edits): nothing
   * re-runs; a step of the history.
   */
  renameOp(opId, name) {
    if (typeof name !== 'string' || name.trim() === '' || name.trim().length > MAX_NAME_LENGTH) {
      return Promise.reject(badParameter(`renameOp(opId, name): name must be text of 1 to ${MAX_NAME_LENGTH} characters, got ${JSON.stringify(name)}`));
    }
    return this.#run(async () => {
      const entry = this.#requireDocument().ops[this.document.indexOf(opId)];
      const before = entry.label;
      const after = name.trim();
      if (before === after) return;
      const named = (label) => async () => {
        entry.label = label;
        this.#persistence.changed();
      };
      await named(after)();
      this.#pushStep(`Rename ${before || entry.id} to ${after}`, named(before), named(after));
    });
  }

  /** Deletes op `opId`: the later ops re-run on its input; a step of the history. */
  removeOp(opId) {
    if (this.#editor.gestureActive) return this.#refusedDuringGesture();
    return this.#run(async () => {
      const index = this.#requireDocument().indexOf(opId);
      const entry = this.document.ops[index];
      const ops = () => this.document.ops;
      const remove = () => this.#rerunAfter(index, () => ops().splice(index, 1), () => ops().splice(index, 0, entry));
      const insert = () => this.#rerunAfter(index, () => ops().splice(index, 0, entry), () => ops().splice(index, 1));
      await remove();
      this.#pushStep(`Delete ${entry.label || entry.id}`, insert, remove);
    });
  }

  /** Moves op `opId` to place `to` (0-based) in the list: the ops from the first place that changed re-run; a step of the history. */
  moveOp(opId, to) {
    if (this.#editor.gestureActive) return this.#refusedDuringGesture();
    const count = this.document?.ops.length ?? 0;
    // The op first: with no such op, the index has no range to be in.
    try {
      this.#requireDocument().indexOf(opId);
    } catch (error) {
      return Promise.reject(error);
    }
    if (!Number.isInteger(to) || to < 0 || to >= count) {
      return Promise.reject(badParameter(`moveOp(opId, index): index must be an integer from 0 to ${count - 1}, got ${JSON.stringify(to)}`));
    }
    return this.#run(async () => {
      const from = this.#requireDocument().indexOf(opId);
      if (from === to) return;
      const entry = this.document.ops[from];
      const move = (a, b) => () => this.document.ops.splice(b, 0, ...this.document.ops.splice(a, 1));
      const there = () => this.#rerunAfter(Math.min(from, to), move(from, to), move(to, from));
      const back = () => this.#rerunAfter(Math.min(from, to), move(to, from), move(from, to));
      await there();
      this.#pushStep(`Move ${entry.label || entry.id} ${to < from ? 'up' : 'down'}`, back, there);
    });
  }

  // Sets op `opId`'s `field` (enabled, op or region) to `value` and re-runs
  // the op and the later ones; then the change is a history step named
  // describe(the op's label). Setting the value it has re-runs, without a step.
  #changeOp(opId, field, value, describe) {
    return this.#run(async () => {
      const entry = this.document.ops[this.#requireDocument().indexOf(opId)];
      const before = entry[field];
      const label = describe(entry.label || entry.id);
      await this.#setOpField(opId, field, value);
      if (JSON.stringify(before) === JSON.stringify(value)) return;
      this.#pushStep(label, () => this.#setOpField(opId, field, before), () => this.#setOpField(opId, field, value));
    });
  }

  // Inside #run: the field set and the op and the later ones re-run. A label
  // the page gave the op follows its method ("Twist (AnDefGrad)").
  #setOpField(opId, field, value) {
    const index = this.#requireDocument().indexOf(opId);
    const entry = this.document.ops[index];
    const before = { [field]: entry[field], label: entry.label };
    return this.#rerunAfter(index, () => {
      entry[field] = value;
      if (field === 'op' && entry.label === describeEdit(before.op)) entry.label = describeEdit(value);
    }, () => Object.assign(entry, before));
  }

  // Inside #run: apply() changes the document, and the ops from `index` on
  // re-run; on failure revert() takes the change back and the document's
  // last state is put back in the worker.
  async #rerunAfter(index, apply, revert) {
    const stats = await this.#solving(async () => {
      apply();
      try {
        return await this.#runner.rerunFrom(index);
      } catch (error) {
        const worded = inPageWords(error, this.document); // while the document names the change
        revert();
        await this.#runner.restore(this.document.ops.length).catch(() => {});
        throw worded;
      }
    });
    this.#persistence.changed();
    this.#reportSolved(stats);
  }

  // A change to the ops becomes a step of the history (undo() and redo()
  // each re-run what they change); as a commit does, it ends what could be
  // redone, the undone ops too.
  #pushStep(label, undo, redo) {
    this.document.undone = [];
    const step = (work) => () => this.#run(work)
      .catch((error) => this.#editor.report(error, `${label} could not be taken back or done again`));
    // Announced (ui/announcer.js): a deletion, a move, an edit turned off
    // change nothing a screen reader otherwise says. A commit says its solve.
    this.#editor.history.push({ label, undo: step(undo), redo: step(redo), announce: true });
  }

  // A committed solve's figures (the status bar's) and its fold-over
  // warning, after the 'change' its positions made (which hides older ones).
  #reportSolved(stats) {
    if (!stats) return;
    this.#editor.emit('stats', { ...stats, live: false });
    if (stats.inverted > 0) this.#editor.emit('warning', { message: foldOverWarning(stats.inverted) });
  }

  // ---- opening and autosave (document-persistence.js) ----------------------

  /** Replays `json` on the current mesh, or on `meshBytes` (named json.mesh.name); on failure the current work stays. */
  open(json, meshBytes, meshName) {
    if (this.#editor.gestureActive) return this.#refusedDuringGesture();
    return this.#persistence.open(json, meshBytes, meshName);
  }

  // The refusal of a change while a drag on the view edits the mesh (editor.refuseDuringGesture).
  #refusedDuringGesture() {
    return Promise.reject(gestureInProgressError());
  }

  /** From now on the work is autosaved (the standalone site; createModeller's `autosave`). */
  enableAutosave() {
    this.#persistence.enableAutosave();
  }

  /** From now on nothing is autosaved, not even saves already asked for (createModeller's dispose). */
  disableAutosave() {
    this.#persistence.disableAutosave();
  }

  /** Restores the autosaved work, if any: null when there was none, else {complete, view} (document-persistence.js). */
  restoreAutosave() {
    return this.#persistence.restoreAutosave();
  }

  /** Autosaves the view of the work beside it (view-autosave.js); `leaving`: the page is going. */
  saveView(view, options) {
    return this.#persistence.saveView(view, options);
  }

  // ---- helpers -------------------------------------------------------------

  // The select steps of the current selection, as an op's region stores them.
  #selectionSteps() {
    const mesh = this.#editor.requireDocument();
    return regionSteps(this.#editor.selectionState.ruleFor(this.restVersion), mesh.selection, mesh.selectionCount);
  }

  #requireDocument() {
    if (!this.document) throw badParameter('no mesh is loaded yet');
    return this.document;
  }

  // One operation at a time; a live preview is left before anything else
  // (the document's last state back in the worker).
  #run(work, { keepLive = false } = {}) {
    const leaving = !keepLive && this.#live.leave();
    return this.#runner.run(async () => {
      if (leaving) await this.#runner.restore(this.document.ops.length, { show: false });
      return work();
    });
  }
}
