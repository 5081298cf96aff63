// The brush outline: a circle at the pointer whose on-screen size matches the
// brush radius at the depth of the surface under the pointer.
import { Vector3 } from 'three';

const centre = new Vector3();
const offset = new Vector3();
const right = new Vector3();

export class BrushCursor {
  constructor(viewer) {
    this.viewer = viewer;
    this.element = document.createElement('div');
    this.element.className = 'brush-cursor';
    this.element.hidden = true;
    viewer.container.append(this.element);
  }

  /**
   * Shows the outline around canvas pixel (x, y) (viewer.canvasPoint's, the
   * unzoomed CSS px its container's layout uses) for a world-space brush at `point`.
   */
  show(x, y, point, radius) {
    const camera = this.viewer.camera;
    centre.fromArray(point);
    right.setFromMatrixColumn(camera.matrixWorld, 0);
    offset.copy(centre).addScaledVector(right, radius);
    const a = centre.clone().project(camera);
    const b = offset.project(camera);
    const pixels = (Math.abs(b.x - a.x) * this.viewer.canvas.clientWidth) / 2;
    Object.assign(this.element.style, {
      left: `${x - pixels}px`,
      top: `${y - pixels}px`,
      width: `${2 * pixels}px`,
      height: `${2 * pixels}px`,
    });
    this.element.hidden = false;
  }

  hide() {
    this.element.hidden = true;
  }
}
