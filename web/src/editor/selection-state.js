// The selection as the page holds it. Regions are the core's: select() asks
// the worker's Session.select (region, falloff, add/subtract), and the page
// keeps a copy of the weights it answers with, to draw them and to undo.
// Brush strokes, grow, shrink, invert and undo change the weights on the
// page; they reach the worker before the next edit, select or flattening.
import { SelectionCommand } from '../commands/selection-command.js';
import { Request } from '../worker/protocol.js';

export class SelectionState {
  #editor;
  #client;
  #beforeChange;
  // What the worker's session holds: a document.selectionVersion, 'whole'
  // (all ones, see syncForEdit) or null (unknown: send again).
  #sent = null;
  // The selection as select steps (the edit document's region rule) while it
  // comes from region selects only, with the rest pose they were evaluated
  // on; null after a brush stroke, grow, invert or undo (then the weights
  // themselves are stored).
  #rule = null;
  #ruleVersion = -1;

  /**
   * @param {{editor: import('./editor.js').Editor, client: object, beforeChange: () => void}} parts
   *   beforeChange runs before every committed change (the pattern of the
   *   selected patch no longer applies).
   */
  constructor({ editor, client, beforeChange }) {
    this.#editor = editor;
    this.#client = client;
    this.#beforeChange = beforeChange;
  }

  /** The worker's selection is unknown (a new mesh, a restarted worker). */
  forget() {
    this.#sent = null;
  }

  /** The core's selection of `region`, committed as one undoable step; resolves with the count. */
  async select(region, options) {
    const editor = this.#editor;
    let document;
    try {
      document = editor.requireDocument();
      editor.refuseDuringGesture();
      // add and subtract combine with the session's selection: it must be the page's.
      this.#send(document.selectionVersion, () => document.selection.slice());
      const restVersion = editor.ops.restVersion;
      const { count, weights } = await this.#client.request(Request.select, { region, options });
      if (editor.document !== document) return count; // a new mesh arrived meanwhile
      const step = { region, ...(options.falloff && { falloff: options.falloff }), ...(options.mode && { mode: options.mode }) };
      const replaces = !options.mode || options.mode === 'replace';
      const base = replaces || document.selectionCount === 0 ? [] : this.ruleFor(restVersion);
      this.commit(weights, 'Select', count);
      this.#rule = base && [...base, step];
      this.#ruleVersion = restVersion;
      this.#sent = document.selectionVersion;
      return count;
    } catch (error) {
      if (document && editor.document === document) this.#sent = null;
      throw editor.report(error, 'The selection was not changed');
    }
  }

  /** The select steps of the selection if they hold on rest pose `restVersion`, else null. */
  ruleFor(restVersion) {
    return this.#rule && this.#ruleVersion === restVersion ? this.#rule : null;
  }

  /**
   * Commits new weights as one undoable step; returns the selected count.
   * Weights equal to the current ones add no step (C with nothing at the
   * view centre, Clear of nothing: the next Undo seemed to do nothing).
   */
  commit(weights, label, count) {
    const document = this.#editor.requireDocument();
    const before = document.selection;
    if (sameWeights(before, weights)) return document.selectionCount;
    this.#apply(weights, count);
    this.#editor.history.push(new SelectionCommand(label, before, weights, (w) => this.#apply(w)));
    return document.selectionCount;
  }

  /**
   * Puts back the selection a reload kept (view-autosave.js), as no step of
   * its own: the history rebuilt from the edits is as it was, and Undo takes
   * back the last edit, not this.
   */
  restore(weights) {
    this.#apply(weights);
  }

  /** Shows weights of a stroke in progress without committing them. */
  show(weights) {
    this.#editor.emit('selection', { weights, count: null, live: true });
  }

  #apply(weights, count) {
    const document = this.#editor.requireDocument();
    this.#rule = null;
    this.#beforeChange();
    document.setSelection(weights, count);
    this.#editor.emit('selection', { weights, count: document.selectionCount, live: false });
    this.#editor.emit('change', { reason: 'selection' });
  }

  // An empty selection means "the whole mesh": a first drag on a freshly
  // loaded mesh does something visible instead of nothing.
  syncForEdit(snapshot = this.snapshotForEdit()) {
    this.#send(snapshot.key, snapshot.weightsOf);
  }

  /**
   * The selection as an edit asked for now uses it, for syncForEdit when the
   * edit runs: an edit queued behind others keeps the selection of its call
   * (deform, deform, select without awaiting solved the second edit on the
   * later selection).
   */
  snapshotForEdit() {
    const document = this.#editor.requireDocument();
    if (document.selectionCount === 0) return { key: 'whole', weightsOf: () => new Float32Array(document.vertexCount).fill(1) };
    // Copied now (the page's weights may change before the edit runs), and
    // sent once: syncForEdit transfers this copy.
    const weights = document.selection.slice();
    return { key: document.selectionVersion, weightsOf: () => weights };
  }

  // Requests are ordered, so the request that follows sees these weights.
  #send(key, weightsOf) {
    if (key === this.#sent) return;
    const weights = weightsOf();
    this.#sent = key;
    this.#client.request(Request.setSelection, { weights }, [weights.buffer]).catch((error) => {
      this.#sent = null;
      this.#editor.report(error, 'The selection could not be sent to the solver');
    });
  }
}

function sameWeights(a, b) {
  if (a.length !== b.length) return false;
  for (let i = 0; i < a.length; i++) if (a[i] !== b[i]) return false;
  return true;
}
