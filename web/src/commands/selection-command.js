// A change of selection weights (a brush stroke, select all, grow, ...).
export class SelectionCommand {
  /**
   * @param {string} label
   * @param {Float32Array} before
   * @param {Float32Array} after
   * @param {(weights: Float32Array) => void} applySelection
   */
  constructor(label, before, after, applySelection) {
    this.label = label;
    this.before = before;
    this.after = after;
    this.applySelection = applySelection;
  }

  /** What the history's memory budget counts (commands/history.js). */
  get bytes() {
    return this.before.byteLength + this.after.byteLength;
  }

  undo() {
    this.applySelection(this.before);
  }

  redo() {
    this.applySelection(this.after);
  }

  toJSON() {
    return { type: 'selection', label: this.label, vertices: this.after.length };
  }
}
