// Committed positions and their history: an edit solved in full and kept as
// one undoable step, reset to the mesh as loaded, and undo/redo restoring
// positions in the worker too.
import { PositionsCommand } from '../commands/positions-command.js';
import { Request } from '../worker/protocol.js';
import { foldOverWarning } from './edit-wording.js';

export class EditCommits {
  #editor;
  #client;
  #dropPattern;

  /** dropPattern: the positions changed, so the last flattening no longer applies. */
  constructor({ editor, client, dropPattern }) {
    this.#editor = editor;
    this.#client = client;
    this.#dropPattern = dropPattern;
  }

  /** Solves `solverOp` fully and commits it as one undoable step. */
  async commit(document, solverOp, label) {
    const editor = this.#editor;
    editor.selectionState.syncForEdit();
    const done = editor.beginBusy();
    try {
      const before = document.positions;
      const { positions, stats, distortion } = await this.#client.request(Request.deform, {
        op: solverOp,
        commit: true,
        distortion: editor.heatMapKind,
      });
      if (editor.document !== document) return stats; // a new mesh arrived meanwhile
      this.#apply(positions, distortion);
      editor.history.push(new PositionsCommand(label, before, positions, (p) => this.#restore(p)));
      editor.emit('stats', { ...stats, live: false });
      if (stats.inverted > 0) editor.emit('warning', { message: foldOverWarning(stats.inverted) });
      return { iterations: stats.iterations, energy: stats.energy, ms: stats.ms, inverted: stats.inverted };
    } catch (error) {
      throw editor.report(error, `${label} failed`);
    } finally {
      done();
    }
  }

  /** Back to the positions as loaded (undoable); false while an edit runs or nothing changed. */
  reset() {
    const editor = this.#editor;
    const document = editor.requireDocument();
    if (editor.gestureActive || editor.busy || document.positions === document.loadedPositions) return false;
    const before = document.positions;
    this.#restore(document.loadedPositions);
    editor.history.push(
      new PositionsCommand('Reset to loaded mesh', before, document.loadedPositions, (p) => this.#restore(p)),
    );
    return true;
  }

  #apply(positions, distortion) {
    this.#dropPattern();
    this.#editor.document.positions = positions;
    this.#editor.emit('positions', { positions, live: false, distortion });
    this.#editor.emit('change', { reason: 'positions' });
  }

  // Undo, redo and reset: the worker's rest mesh follows (a copy is sent,
  // because the history keeps the original).
  #restore(positions) {
    const copy = positions.slice();
    this.#client.request(Request.setPositions, { positions: copy }, [copy.buffer]).catch((error) => {
      this.#editor.report(error, 'The solver could not restore the positions');
    });
    this.#apply(positions);
  }
}
