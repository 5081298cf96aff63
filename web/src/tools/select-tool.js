// Selection brush: press and drag on the mesh to paint selection weights
// (BVH sphere queries around the surface point under the pointer). The
// stroke is shown live and committed as one undo step on release; Esc drops
// it. Shift inverts the brush mode (add ↔ subtract) for that stroke.
import { paintDab, strokePoints } from '../interaction/selection-brush.js';

export class SelectTool {
  id = 'select';
  label = 'Select';
  hint = 'Paint on the mesh to select (Shift: erase). Drag off the mesh to orbit.';
  stroke = null;

  constructor({ editor, picker, settings, brushCursor }) {
    this.editor = editor;
    this.picker = picker;
    this.settings = settings;
    this.brushCursor = brushCursor;
  }

  #radius() {
    const { diagonal } = this.editor.document.bounds();
    return (this.settings.values.brush.radiusPercent / 100) * diagonal;
  }

  // While a committed solve runs, a press on the mesh turns the view (the
  // brush is off, as Apply is) and says why it does not paint.
  wantsGesture(hit) {
    if (hit === null || this.editor.gestureActive) return false;
    return !this.editor.refusedWhileBusy('Painting the selection');
  }

  start({ hit, event }) {
    const { mode, softnessPercent } = this.settings.values.brush;
    const before = this.editor.document.selection;
    this.stroke = {
      before,
      weights: before.slice(),
      mode: event.shiftKey ? (mode === 'add' ? 'subtract' : 'add') : mode,
      radius: this.#radius(),
      softness: softnessPercent / 100,
      last: hit.point,
    };
    this.#dab(hit.point);
  }

  move({ x, y }) {
    const stroke = this.stroke;
    if (!stroke) return;
    const hit = this.picker.pick(x, y);
    if (!hit) return;
    this.brushCursor.show(x, y, hit.point, stroke.radius);
    for (const point of strokePoints(stroke.last, hit.point, stroke.radius / 3)) this.#dab(point);
    stroke.last = hit.point;
  }

  #dab(point) {
    const { weights, radius, softness, mode } = this.stroke;
    if (paintDab(weights, this.picker, point, radius, softness, mode) > 0) this.editor.showSelection(weights);
  }

  end() {
    const stroke = this.stroke;
    this.stroke = null;
    if (stroke) this.editor.setSelection(stroke.weights, stroke.mode === 'add' ? 'Brush' : 'Brush (erase)');
  }

  cancel() {
    const stroke = this.stroke;
    this.stroke = null;
    if (stroke) this.editor.showSelection(stroke.before);
  }

  hover(pointer) {
    if (pointer?.hit) this.brushCursor.show(pointer.x, pointer.y, pointer.hit.point, this.#radius());
    else this.brushCursor.hide();
  }

  deactivate() {
    this.brushCursor.hide();
  }
}
