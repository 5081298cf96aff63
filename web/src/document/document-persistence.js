// The edit document in and out of the page: open() replays a document (on
// the current mesh or on given mesh bytes) and makes it the stack's; after
// every change the document is announced ('document') and autosaved with the
// mesh bytes (autosave.js), and a reload restores that work.
import { EditDocument, withMeshFileName } from './edit-document.js';
import { Autosave } from './autosave.js';
import { badParameter } from '../shared/errors.js';

export class DocumentPersistence {
  #editor;
  #runner;
  #run;
  #stack;
  #rebuildHistory;
  #reportSolved;
  #autosave = new Autosave();
  // The announcement waiting for the operation running to end (announce), or null.
  #announcing = null;
  /** The base mesh as loaded: {name, bytes: a Blob of the file}. */
  mesh = null;
  /** True while the autosaved mesh is being loaded (its load must not replace the autosave). */
  restoring = false;

  /**
   * stack: the OpStack (its `document` is read and replaced here); runner:
   * its OpRunner; run(work): its one-at-a-time runner; rebuildHistory():
   * makes the history of the document just adopted.
   */
  constructor({ editor, stack, runner, run, rebuildHistory, reportSolved }) {
    this.#reportSolved = reportSolved;
    this.#editor = editor;
    this.#stack = stack;
    this.#runner = runner;
    this.#run = run;
    this.#rebuildHistory = rebuildHistory;
  }

  /**
   * Replays `json` on the current mesh, or on `meshBytes`, read as the file
   * `meshName` (default json.mesh.name); on failure the current work stays.
   * The document's own name of its mesh is what a refusal quotes (the file
   * it was made on); once opened, it takes the file's name.
   */
  open(json, meshBytes, meshName) {
    const editor = this.#editor;
    return this.#run(async () => {
      if (!json || typeof json !== 'object') throw badParameter('open() needs an edit document object');
      const current = this.#stack.document;
      const previous = current && { json: current.toJSON(), mesh: this.mesh };
      if (meshBytes !== undefined) await editor.load(meshBytes, meshName ?? json.mesh?.name);
      else if (!this.#stack.document) throw badParameter('no mesh is loaded yet');
      let replayed;
      try {
        replayed = await this.#replayEach(json);
      } catch (error) {
        // The work is put back (the ops before the failing one stay in the
        // session as its rest pose): the mesh loaded for the document undone,
        // or the state on screen, that of the current document (when the
        // page had none, the mesh loaded for this one, as loaded).
        if (meshBytes !== undefined && previous) await this.#reopen(previous);
        else if (this.#stack.document) await this.#runner.restore(this.#stack.document.ops.length).catch(() => {});
        throw meshBytes === undefined ? error : namingMeshFile(error, meshName ?? json.mesh?.name);
      }
      this.#adopt(meshBytes !== undefined ? withMeshFileName(json, meshName) : json, replayed);
    });
  }

  // The ops of `json` replayed one at a time from the mesh as loaded, so
  // that the progress says which one runs ("Edit 2 of 5: Solving 40 %") and
  // the states between them are kept for undo. The first call checks the
  // whole document, so a bad one is refused before anything is solved.
  async #replayEach(json, options = {}) {
    const n = Array.isArray(json.ops) ? json.ops.length : 0;
    if (n === 0) return { states: [], result: await this.#runner.replay(0, 0, { json, ...options }) };
    const states = [];
    let result;
    for (let i = 0; i < n; i++) {
      // The heat map's values only for the state shown.
      const last = i === n - 1 ? {} : { distortion: null };
      result = await this.#runner.replay(i, i + 1, { json, label: `Edit ${i + 1} of ${n}`, ...last, ...options });
      if (i < n - 1) states.push({ positions: result.positions, exact: result.exact });
    }
    return { states, result };
  }

  async #reopen({ json, mesh }) {
    await this.#editor.load(mesh.bytes, mesh.name);
    this.#adopt(json, await this.#replayEach(json, { distortion: null }));
  }

  #adopt(json, { states, result }) {
    const cache = this.#runner.cache;
    const state0 = cache.get(0);
    const document = EditDocument.fromJSON(json);
    this.#stack.document = document;
    cache.clear();
    cache.set(0, state0);
    states.forEach((state, k) => cache.set(k + 1, state));
    this.#runner.show(document.ops.length, result);
    this.#rebuildHistory();
    this.changed();
    // As a commit does: the status bar's figures, a fold-over warning, and an
    // earlier error put behind (a refused open's stayed over the opened edits).
    this.#reportSolved(result.summary?.last ?? null);
  }

  /**
   * Announces the document ('document', and a 'change' unless change is
   * false), once the operation that changed it has ended: a listener may
   * start the next one. (The API's "undo again after each step's 'document'
   * event" was refused as busy: the event came while the re-run still ran.)
   * Changes within one operation are announced once.
   */
  announce({ change = true } = {}) {
    if (this.#announcing) {
      this.#announcing.change ||= change;
      return;
    }
    const announcing = { change };
    this.#announcing = announcing;
    this.#editor.afterOperation(() => {
      this.#announcing = null;
      this.#editor.emit('document', this.#stack.document);
      if (announcing.change) this.#editor.emit('change', { reason: 'document' });
    });
  }

  /** Announces the document and autosaves it with the mesh bytes. */
  changed({ change = true } = {}) {
    this.announce({ change });
    const { name, bytes } = this.mesh;
    this.#autosave.save({ document: this.#stack.document.toJSON(), meshName: name, meshBytes: bytes })
      .catch((error) => this.#editor.report(error, 'Autosave'));
  }

  /** From now on the work is autosaved (the standalone site; createModeller's `autosave`). */
  enableAutosave() {
    this.#autosave.enabled = true;
  }

  /** From now on nothing is autosaved, not even saves already asked for (createModeller's dispose). */
  disableAutosave() {
    this.#autosave.enabled = false;
  }

  /** Autosaves the view of the work (view-autosave.js) beside it; `leaving`: the page is going. */
  saveView(view, options) {
    return this.#autosave.saveView(view, options);
  }

  /**
   * Restores the autosaved work, if any. Resolves null when no saved mesh
   * was loaded, else {complete, view}: complete, whether all its edits were
   * put back (not stopped, not failed); view, the view saved beside it
   * (view-autosave.js), or null.
   */
  async restoreAutosave() {
    const record = await this.#autosave.load().catch((error) => {
      this.#editor.report(error, 'Autosave');
      return null;
    });
    if (!record) return null;
    this.restoring = true;
    try {
      await this.#editor.load(record.meshBytes, record.meshName);
    } finally {
      this.restoring = false;
    }
    // A view that cannot be read leaves the work as restored, the view as a new page has it.
    const view = this.#autosave.loadView().catch(() => null);
    const complete = await this.open(record.document).then(() => true, (error) => {
      // Stopped (Esc while it replays), the saved work is not lost yet: the
      // record stays until the next change here is saved over it. The
      // cancel's own words ("the history is as it was") hid that a first
      // edit then replaced every saved edit.
      if (error?.code === 'cancelled') this.#editor.report(restoreStoppedError(record.document?.ops?.length ?? 0));
      else this.#editor.report(error, 'The saved work could not be replayed');
      return false;
    });
    return { complete, view: await view };
  }
}

function restoreStoppedError(edits) {
  const message = `Putting back the saved work was stopped: its ${edits} edit${edits === 1 ? '' : 's'} stay saved, and `
    + 'reloading the page puts them back; the next edit made here replaces them.';
  return Object.assign(new Error(message), { code: 'cancelled' });
}

// A refusal of the mesh file given with the document: "the loaded mesh" is
// no longer on screen once the work is put back; the file is named instead.
function namingMeshFile(error, fileName) {
  if (typeof error?.message !== 'string' || !fileName || !error.message.includes('the loaded mesh')) return error;
  return Object.assign(new Error(error.message.replace('the loaded mesh', `the mesh of ${fileName}`)), { code: error.code, cause: error });
}
