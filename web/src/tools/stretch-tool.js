// Stretch: scale along the direction (su) and optionally across it (sv).
// A drag stretches along the dragged direction; Shift+drag squashes.
import { TransformTool } from './transform-tool.js';

export class StretchTool extends TransformTool {
  id = 'stretch';
  label = 'Stretch';
  hint = 'Drag on the mesh: the selection stretches along the drag (Shift: squash).';
  fields = [
    { key: 'along', label: 'Along ×', step: 0.05 },
    { key: 'across', label: 'Across ×', step: 0.05 },
  ];

  transformForDrag(amount, invert) {
    const along = round(invert ? 1 / (1 + amount) : 1 + amount);
    this.settings.update('stretch', { along });
    return { scale: [along, this.settings.values.stretch.across] };
  }

  transformFromSettings() {
    const { along, across } = this.settings.values.stretch;
    return { scale: [along, across] };
  }
}

export function round(value, digits = 3) {
  const factor = 10 ** digits;
  return Math.round(value * factor) / factor;
}
