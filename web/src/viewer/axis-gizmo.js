// A small axis gizmo in the viewport's bottom left corner: the world's X, Y
// and Z (red, green, blue, as in Blender and three.js) as seen from the
// camera, redrawn with every frame, the nearer axes in front. An SVG over
// the canvas (no second render pass); styled inline for embedded viewers.
import { Vector3 } from 'three';

const SIZE = 64;
const LENGTH = 22;
const AXES = [
  { name: 'X', vector: new Vector3(1, 0, 0), color: '#e5484d' },
  { name: 'Y', vector: new Vector3(0, 1, 0), color: '#46a758' },
  { name: 'Z', vector: new Vector3(0, 0, 1), color: '#3e8ef7' },
];
const SVG = 'http://www.w3.org/2000/svg';

export class AxisGizmo {
  #view = new Vector3();

  constructor(viewer, lifetime) {
    this.viewer = viewer;
    this.svg = svgElement('svg', { width: SIZE, height: SIZE, viewBox: `0 0 ${SIZE} ${SIZE}`, role: 'img' });
    this.svg.dataset.testid = 'axis-gizmo';
    Object.assign(this.svg.style, { position: 'absolute', left: '8px', bottom: '8px', pointerEvents: 'none' });
    this.axes = AXES.map(({ name, color }) => {
      const group = svgElement('g', {});
      group.dataset.axis = name;
      const line = svgElement('line', { x1: SIZE / 2, y1: SIZE / 2, stroke: color, 'stroke-width': 2.5, 'stroke-linecap': 'round' });
      const label = svgElement('text', { fill: color, 'font-size': 11, 'font-family': 'system-ui, sans-serif', 'font-weight': 'bold', 'text-anchor': 'middle', 'dominant-baseline': 'central' });
      label.textContent = name;
      group.append(line, label);
      this.svg.append(group);
      return { group, line, label };
    });
    viewer.container.append(this.svg);
    lifetime.defer(viewer.on('frame', () => this.update()));
    this.update();
  }

  update() {
    const toView = this.viewer.camera.quaternion.clone().invert();
    const placed = AXES.map((axis, index) => {
      const v = this.#view.copy(axis.vector).applyQuaternion(toView);
      return { index, x: SIZE / 2 + LENGTH * v.x, y: SIZE / 2 - LENGTH * v.y, depth: v.z };
    });
    // Painter's order: the axis pointing away from the viewer first.
    placed.sort((a, b) => a.depth - b.depth);
    const names = [];
    for (const { index, x, y } of placed) {
      const { group, line, label } = this.axes[index];
      line.setAttribute('x2', x.toFixed(1));
      line.setAttribute('y2', y.toFixed(1));
      const dx = x - SIZE / 2, dy = y - SIZE / 2, length = Math.hypot(dx, dy) || 1;
      label.setAttribute('x', (x + (7 * dx) / length).toFixed(1));
      label.setAttribute('y', (y + (7 * dy) / length).toFixed(1));
      this.svg.append(group);
      names.push(AXES[index].name);
    }
    this.svg.setAttribute('aria-label', `Axes as seen from the camera (front last: ${names.join(', ')})`);
  }
}

function svgElement(tag, attributes) {
  const element = document.createElementNS(SVG, tag);
  for (const [key, value] of Object.entries(attributes)) element.setAttribute(key, String(value));
  return element;
}
