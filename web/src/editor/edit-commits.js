// Committed edits: an edit solved in full and kept as one op of the edit
// document (document/op-stack.js), which also gives undo/redo over the ops
// and reset to the mesh as loaded.
import { OpStack } from '../document/op-stack.js';

export class EditCommits {
  #editor;
  /** @type {OpStack} */
  ops;

  /** dropPattern: the positions changed, so the last flattening no longer applies. */
  constructor({ editor, client, dropPattern }) {
    this.#editor = editor;
    this.ops = new OpStack({ editor, client, dropPattern });
  }

  /** Solves `solverOp` fully and commits it as one undoable op. */
  async commit(document, solverOp, label) {
    const editor = this.#editor;
    try {
      if (editor.document !== document) return null; // a new mesh arrived meanwhile
      const stats = await this.ops.commit(solverOp, label);
      return stats && {
        iterations: stats.iterations, energy: stats.energy, ms: stats.ms, inverted: stats.inverted, converged: stats.converged,
      };
    } catch (error) {
      throw editor.report(error, `${label} failed`);
    }
  }

  /** Back to the mesh as loaded (undoable); false while an edit runs or nothing changed. */
  reset() {
    const editor = this.#editor;
    editor.requireDocument();
    if (editor.gestureActive || editor.busy) return false;
    return this.ops.reset();
  }
}
