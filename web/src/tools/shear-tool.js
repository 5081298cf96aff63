// Shear: the tangent plane slides along the direction, by h per unit across
// it (METHOD §3). Drag: positive shear; Shift+drag: negative.
import { round } from './stretch-tool.js';
import { TransformTool } from './transform-tool.js';

export class ShearTool extends TransformTool {
  id = 'shear';
  label = 'Shear';
  hint = 'Drag on the mesh: shear along the direction (Shift: the other way).';
  fields = [{ key: 'amount', label: 'Shear h', step: 0.05 }];

  transformForDrag(amount, invert) {
    const shear = round(invert ? -amount : amount);
    this.settings.update('shear', { amount: shear });
    return { shear };
  }

  transformFromSettings() {
    return { shear: this.settings.values.shear.amount };
  }
}
