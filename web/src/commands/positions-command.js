// An edit of vertex positions (a deformation or a reset): keeps the positions
// before and after. Both arrays are shared, never written (see MeshDocument),
// so consecutive edits share their middle array.
export class PositionsCommand {
  /**
   * @param {string} label                   e.g. "Stretch (AnARAP)"
   * @param {Float32Array} before
   * @param {Float32Array} after
   * @param {(positions: Float32Array) => void} applyPositions
   */
  constructor(label, before, after, applyPositions) {
    this.label = label;
    this.before = before;
    this.after = after;
    this.applyPositions = applyPositions;
  }

  undo() {
    this.applyPositions(this.before);
  }

  redo() {
    this.applyPositions(this.after);
  }

  toJSON() {
    return { type: 'positions', label: this.label, vertices: this.after.length / 3 };
  }
}
