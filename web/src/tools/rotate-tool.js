// Rotate: each element turns about its normal (n) or a tangent axis (u along
// the direction, v across it) by the given angle, blended by weight.
// Drag: 90° per selection length dragged; Shift+drag: the other way.
import { round } from './stretch-tool.js';
import { TransformTool } from './transform-tool.js';

export class RotateTool extends TransformTool {
  id = 'rotate';
  label = 'Rotate';
  hint = 'Drag on the mesh: rotate each element about the chosen axis (Shift: the other way).';
  fields = [
    {
      key: 'axis',
      label: 'Axis',
      options: [
        ['n', 'Normal (n)'],
        ['u', 'Along direction (u)'],
        ['v', 'Across direction (v)'],
      ],
    },
    { key: 'degrees', label: 'Degrees', step: 1 },
  ];

  transformForDrag(amount, invert) {
    const degrees = round((invert ? -1 : 1) * amount * 90, 1);
    this.settings.update('rotate', { degrees });
    return { rotate: { axis: this.settings.values.rotate.axis, degrees } };
  }

  transformFromSettings() {
    const { axis, degrees } = this.settings.values.rotate;
    return { rotate: { axis, degrees } };
  }
}
