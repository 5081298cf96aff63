// Twist: rotation about a global axis by an angle that grows along it
// (degrees per model unit; paper Fig. 6). Drag: a full selection length
// dragged gives 180° over the selection; Shift+drag twists the other way.
import { axisVector } from '../editor/settings.js';
import { extentAlong } from '../interaction/screen-drag.js';
import { round } from './stretch-tool.js';
import { TransformTool } from './transform-tool.js';

export class TwistTool extends TransformTool {
  id = 'twist';
  label = 'Twist';
  hint = 'Drag on the mesh: twist about the axis, more the farther along it (Shift: the other way).';
  fields = [
    {
      key: 'axis',
      label: 'Axis',
      options: [
        ['x', 'X'],
        ['y', 'Y'],
        ['z', 'Z'],
        ['custom', 'Custom'],
      ],
    },
    { key: 'custom', label: 'Custom axis', vector: true, showWhen: (values) => values.axis === 'custom' },
    { key: 'degreesPerUnit', label: '° per unit', min: -36000, max: 36000, step: 1 },
  ];

  #axis() {
    const { axis, custom } = this.settings.values.twist;
    const vector = axisVector(axis, custom);
    const length = Math.hypot(...vector);
    return vector.map((value) => value / length);
  }

  transformForDrag(amount, invert) {
    const axis = this.#axis();
    const length = Math.max(extentAlong(this.editor.document, axis), 1e-9);
    const degreesPerUnit = round(((invert ? -1 : 1) * amount * 180) / length, 1);
    this.settings.update('twist', { degreesPerUnit });
    return { twist: { axis, degreesPerUnit } };
  }

  transformFromSettings() {
    return { twist: { axis: this.#axis(), degreesPerUnit: this.settings.values.twist.degreesPerUnit } };
  }
}
