// The live edit (a drag): begin, a preview per pointer move (the solver
// client keeps only the latest one waiting), settling while the pointer
// rests (settling.js), then commit as one undoable step, or cancel. One at
// a time, and none while a committed edit is solved.
import { Request } from '../worker/protocol.js';
import { settleNext } from './settling.js';
import { toSolverOp } from './solver-op.js';

export class GestureController {
  #editor;
  #client;
  #gesture = null;
  #count = 0;

  constructor({ editor, client }) {
    this.#editor = editor;
    this.#client = client;
  }

  get active() {
    return this.#gesture !== null;
  }

  /** Starts a live edit. Returns false while another edit runs. */
  begin() {
    const editor = this.#editor;
    if (!editor.document || this.#gesture || editor.busy) return false;
    this.#gesture = { id: ++this.#count, lastOp: null };
    editor.selectionState.syncForEdit();
    editor.emit('gesture', true);
    return true;
  }

  /** Shows the edit `op` live; stale results are dropped. */
  update(op) {
    const gesture = this.#gesture;
    if (!gesture) return;
    const editor = this.#editor;
    const solverOp = toSolverOp(op, editor.document, editor.view);
    gesture.lastOp = solverOp;
    gesture.movedAt = performance.now();
    this.#preview(gesture, solverOp, null, undefined);  // the client's one-iteration default
  }

  /** Shows `solverOp` live, then settles it while it stays the gesture's last. */
  #preview(gesture, solverOp, previousEnergy, iterations) {
    const editor = this.#editor;
    this.#client
      .preview(solverOp, editor.heatMapKind, iterations)
      .then((result) => {
        if (!result || this.#gesture !== gesture) return;
        editor.emit('positions', { positions: result.positions, live: true, distortion: result.distortion });
        editor.emit('stats', { ...result.stats, live: true });
        this.#settle(gesture, solverOp, previousEnergy, result.stats);
      })
      .catch((error) => {
        if (this.#gesture === gesture) editor.report(error, 'The live preview failed');
      });
  }

  #settle(gesture, solverOp, previousEnergy, stats) {
    settleNext({
      stats,
      previousEnergy,
      changedAt: gesture.movedAt,
      current: () => this.#gesture === gesture && gesture.lastOp === solverOp,
      next: (iterations, energy) => this.#preview(gesture, solverOp, energy, iterations),
    });
  }

  /** Ends the live edit and commits its last state (fully solved) as one step. */
  async commit(label) {
    const gesture = this.#gesture;
    if (!gesture) return null;
    const editor = this.#editor;
    this.abandon();
    if (!gesture.lastOp) {
      await this.#client.request(Request.cancel).catch((error) => {
        throw editor.report(error, 'Cancel failed');
      });
      return null;
    }
    const { preview, ...finalOp } = gesture.lastOp;
    return editor.commitEdit(editor.document, finalOp, label);
  }

  /** Esc: drops the live edit; the mesh returns to its committed state. */
  cancel() {
    if (!this.#gesture) return false;
    const editor = this.#editor;
    this.abandon();
    this.#client.request(Request.cancel).catch((error) => editor.report(error, 'Cancel failed'));
    editor.emit('positions', { positions: editor.document.positions, live: false });
    return true;
  }

  /** Forgets the live edit without a word to the worker (a new mesh replaces it). */
  abandon() {
    if (!this.#gesture) return;
    this.#gesture = null;
    this.#client.dropQueuedPreview();
    this.#editor.emit('gesture', false);
  }
}
