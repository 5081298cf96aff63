// Arrows: press on the surface and drag to place a direction constraint at
// the vertex under the pointer; the tangent direction there that is seen
// running along the drag is its direction. The solver propagates the arrows to
// a smooth line field (direction source 'arrows'). Placing an arrow selects
// that source (the Flatten panel's in flatten mode).
import { surfaceDragDirection } from '../interaction/screen-drag.js';

const DRAG_THRESHOLD_PX = 4;

export class ArrowTool {
  id = 'arrows';
  label = 'Arrows';
  hint = 'Drag on the surface to place an arrow; the arrows are spread into a smooth direction field.';
  gesture = null;

  constructor({ editor, viewer, settings, arrowPreview }) {
    this.editor = editor;
    this.viewer = viewer;
    this.settings = settings;
    this.arrowPreview = arrowPreview;
  }

  wantsGesture(hit) {
    return hit !== null && !this.editor.gestureActive;
  }

  start({ x, y, hit }) {
    this.gesture = { from: [x, y], hit, direction: null };
  }

  move({ x, y }) {
    const gesture = this.gesture;
    if (!gesture || Math.hypot(x - gesture.from[0], y - gesture.from[1]) < DRAG_THRESHOLD_PX) return;
    gesture.direction = surfaceDragDirection(this.viewer, gesture.from, [x, y], gesture.hit);
    this.arrowPreview([...this.settings.values.arrows, this.#arrow(gesture)]);
  }

  #arrow(gesture) {
    return { vertex: gesture.hit.vertex, point: gesture.hit.point, direction: gesture.direction };
  }

  end() {
    const gesture = this.gesture;
    this.gesture = null;
    if (!gesture?.direction || gesture.direction.every((value) => value === 0)) return;
    this.settings.update('arrows', [...this.settings.values.arrows, this.#arrow(gesture)]);
    this.settings.update(this.settings.values.mode === 'flatten' ? 'flatten' : 'direction', { source: 'arrows' });
  }

  cancel() {
    this.gesture = null;
    this.arrowPreview(this.settings.values.arrows);
  }
}
