// The shared stroke pipeline of every transform tool (stretch, thicken,
// shear, rotate, twist); each tool file only says how an amount becomes a
// transform.
//
//   press on the mesh  → the hit point is the anchor; the editor starts a live edit
//   drag               → the drag, unprojected at the anchor's depth, gives
//                        the world drag vector d; t = |d| / extent of the
//                        selection along d is the amount (Shift inverts it);
//                        with the 'screen' direction source the drag is also
//                        the direction; the op goes to the worker as a
//                        coalesced, warm-started preview
//                        and its amount is shown beside the pointer
//   release            → the last op is solved fully and committed (one undo step)
//   Esc                → the live edit is dropped, and the amount the drag
//                        wrote to the panel is put back (Apply would use it)
//
// With the method 'arap' (ARAP with handles) the drag moves the selection
// instead: op.move = d.
import { describeEdit } from '../editor/edit-wording.js';
import { dragAmountText } from '../interaction/drag-readout.js';
import { extentAlong, normalized, worldDragVector } from '../interaction/screen-drag.js';
import { directionFromSettings, transformUsesDirection } from './direction-source.js';
import { badParameter } from '../shared/errors.js';

// Below this many pixels a press is a click, not a drag.
const DRAG_THRESHOLD_PX = 3;

export class TransformTool {
  gesture = null;

  /**
   * @param {{editor: import('../editor/editor.js').Editor, viewer: import('../viewer/viewer.js').Viewer,
   *          settings: import('../shared/settings.js').Settings, reportError: (error: Error) => void,
   *          dragReadout: import('../interaction/drag-readout.js').DragReadout}} context
   */
  constructor(context) {
    this.editor = context.editor;
    this.viewer = context.viewer;
    this.settings = context.settings;
    this.reportError = context.reportError;
    this.dragReadout = context.dragReadout;
  }

  // As the brush (select-tool.js): while a committed solve runs, a press on
  // the mesh turns the view and says why it does not edit.
  wantsGesture(hit) {
    return hit !== null && !this.editor.refusedWhileBusy('Dragging an edit');
  }

  start({ x, y, hit }) {
    if (!this.editor.beginGesture()) return;
    this.gesture = { from: [x, y], anchor: hit.point, normal: hit.normal, camera: this.viewer.cameraState(), op: null,
      amounts: structuredClone(this.settings.values[this.id]) };
  }

  move({ x, y, event }) {
    const gesture = this.gesture;
    if (!gesture) return;
    if (Math.hypot(x - gesture.from[0], y - gesture.from[1]) < DRAG_THRESHOLD_PX) return;
    try {
      gesture.op = this.#opForDrag(gesture, [x, y], event.shiftKey);
      this.editor.updateGesture(gesture.op);
      this.dragReadout.show(x, y, dragAmountText(this.id, gesture.op));
    } catch (error) {
      this.cancel();
      this.reportError(error);
    }
  }

  end() {
    const gesture = this.gesture;
    this.gesture = null;
    this.dragReadout.hide();
    if (!gesture) return;
    if (!gesture.op) this.click?.(gesture.anchor);
    if (gesture.op?.direction?.type === 'screen') this.settings.update('lastScreen', gesture.op.direction);
    // On failure the mesh stays as committed; the editor has shown its own errors.
    this.editor.commitGesture(gesture.op ? describeEdit(gesture.op) : '').catch(this.reportError);
  }

  cancel() {
    const gesture = this.gesture;
    this.gesture = null;
    // The drag writes its amount to the tool's settings (its id's) as it goes.
    if (gesture?.op && gesture.amounts) this.settings.update(this.id, gesture.amounts);
    this.dragReadout.hide();
    this.editor.cancelGesture();
  }

  #opForDrag(gesture, to, invert) {
    const values = this.settings.values;
    const dragWorld = worldDragVector(this.viewer, gesture.from, to, gesture.anchor);
    if (values.solver.method === 'arap') {
      return { method: 'arap', move: dragWorld, maxIterations: values.solver.iterations };
    }
    const direction =
      values.direction.source === 'screen'
        ? { type: 'screen', from: gesture.from, to,
            camera: { ...gesture.camera, anchor: gesture.anchor, normal: gesture.normal } }
        : directionFromSettings(values);
    const document = this.editor.document;
    const dragLength = Math.hypot(...dragWorld);
    // A small selection still needs a usable scale: at least 5% of the mesh size.
    const extent = Math.max(extentAlong(document, normalized(dragWorld)), 0.05 * document.bounds().diagonal);
    const amount = dragLength / extent;
    const transform = this.transformForDrag(amount, invert);
    return { method: values.solver.method, direction, transform, maxIterations: values.solver.iterations };
  }

  /** Applies the numeric amounts of the panel as one committed edit. */
  async apply() {
    const values = this.settings.values;
    if (values.solver.method === 'arap') {
      throw badParameter('ARAP with handles has no amount to apply: drag the selection on the mesh, or choose another method');
    }
    const transform = this.transformFromSettings();
    const op = {
      method: values.solver.method,
      ...(transformUsesDirection(transform) && { direction: directionFromSettings(values) }),
      transform,
      maxIterations: values.solver.iterations,
    };
    return this.editor.deform(op, describeEdit(op));
  }

  // Subclasses: transformForDrag(amount, invert) writes the amount back to
  // the settings and returns the transform; transformFromSettings() returns
  // the transform of the numeric fields; `fields` describes those fields;
  // click(point), if present, gets the surface point of a press without a drag.
}
