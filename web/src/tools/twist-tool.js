// Twist: rotation about an axis line by an angle that grows along it
// (degrees per model unit; paper Fig. 6). Drag: a full selection length
// dragged gives 180° over the selection; Shift+drag twists the other way.
// The axis line runs through the selection's weighted centroid (the core's
// default) or through a point: typed, or clicked on the mesh.
import { axisVector } from '../shared/settings.js';
import { extentAlong } from '../interaction/screen-drag.js';
import { TransformTool } from './transform-tool.js';

const QUARTER_TURN = 90;

export class TwistTool extends TransformTool {
  id = 'twist';
  label = 'Twist';
  hint = 'Drag on the mesh: twist about the axis, more the farther along it (Shift: the other way). Click: the axis passes there.';
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
    {
      key: 'origin',
      label: 'Origin',
      options: [
        ['centroid', 'Centroid of selection'],
        ['point', 'Point (click the mesh)'],
      ],
    },
    { key: 'point', label: 'Origin point', vector: true, point: true, showWhen: (values) => values.origin === 'point' },
    { key: 'degreesPerUnit', label: '° per unit', step: 'any' },
  ];

  constructor(context) {
    super(context);
    // A rate in degrees per model unit means nothing on another mesh (Spot
    // is 1.7 units tall, the armadillo 151: its 90 degrees per unit folded
    // the armadillo's upper half into shards). Each load sets it to a
    // quarter turn over the new mesh's extent along the axis (its bounding
    // box's, kept by the document: no pass over the vertices at a load).
    this.editor.on('mesh', (document) => {
      const { min, max, diagonal } = document.bounds();
      const axis = this.#axis();
      const extent = axis.reduce((sum, a, k) => sum + Math.abs(a) * (max[k] - min[k]), 0) || diagonal;
      if (!(extent > 0)) return; // a mesh of one point: no size to measure a turn by
      this.settings.update('twist', { degreesPerUnit: Number((QUARTER_TURN / extent).toPrecision(2)) });
    });
  }

  #axis() {
    const { axis, custom } = this.settings.values.twist;
    const vector = axisVector(axis, custom);
    const length = Math.hypot(...vector);
    return vector.map((value) => value / length);
  }

  // Without an origin the core takes the selection's centroid line.
  #twist(degreesPerUnit) {
    const { origin, point } = this.settings.values.twist;
    return { axis: this.#axis(), degreesPerUnit, ...(origin === 'point' && { origin: [...point] }) };
  }

  click(point) {
    this.settings.update('twist', { origin: 'point', point: [...point] });
  }

  transformForDrag(amount, invert) {
    const axis = this.#axis();
    const length = Math.max(extentAlong(this.editor.document, axis), 1e-9);
    // Three significant digits, not a fixed 0.1: a rate per unit depends on
    // the mesh's size (on the 151-unit armadillo a step of 0.1 per unit was
    // 15 degrees of twist, and its 0.59 default could not be dragged to).
    const degreesPerUnit = Number((((invert ? -1 : 1) * amount * 180) / length).toPrecision(3));
    this.settings.update('twist', { degreesPerUnit });
    return { twist: this.#twist(degreesPerUnit) };
  }

  transformFromSettings() {
    return { twist: this.#twist(this.settings.values.twist.degreesPerUnit) };
  }
}
