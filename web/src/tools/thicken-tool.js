// Thicken / squash: scale across the direction in the tangent plane (sv),
// keeping the length along it, e.g. a leg gets thicker but not longer when
// the direction runs along the leg. Drag: thicker; Shift+drag: thinner.
import { round } from './stretch-tool.js';
import { TransformTool } from './transform-tool.js';

export class ThickenTool extends TransformTool {
  id = 'thicken';
  label = 'Thicken';
  hint = 'Drag on the mesh: thicker across the direction (Shift: thinner).';
  fields = [{ key: 'factor', label: 'Across ×', step: 0.05 }];

  transformForDrag(amount, invert) {
    const factor = round(invert ? 1 / (1 + amount) : 1 + amount);
    this.settings.update('thicken', { factor });
    return { scale: [1, factor] };
  }

  transformFromSettings() {
    return { scale: [1, this.settings.values.thicken.factor] };
  }
}
