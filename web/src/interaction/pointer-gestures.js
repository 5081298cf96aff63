// The one place that decides who gets a pointer gesture on the canvas: the
// active tool when a left-button press lands on the mesh (or the tool wants
// presses off the mesh too), otherwise the orbit controls. It listens in the
// capture phase, so it runs before OrbitControls and can keep it out of a
// tool's drag. Pointer capture keeps the drag alive outside the canvas. A
// double-click on the mesh moves the orbit target there.
// A second finger turns a tool's stroke into a camera gesture (pinch, two-
// finger pan): the stroke is cancelled as if it never started (no paint, no
// edit, no undo step) and both touches go to the orbit controls, which are
// told about the first one with a pointerdown at its latest position.
export class PointerGestures {
  #active = null;
  #handingOver = false;

  /**
   * @param {import('../viewer/viewer.js').Viewer} viewer
   * @param {import('./picker.js').Picker} picker
   * @param {() => object|null} activeTool  the tool under the pointer, or null
   * @param {import('../embed/lifetime.js').Lifetime} lifetime
   */
  constructor(viewer, picker, activeTool, lifetime) {
    this.viewer = viewer;
    this.picker = picker;
    this.activeTool = activeTool;
    const canvas = viewer.canvas;
    lifetime.listen(canvas, 'pointerdown', (event) => this.#down(event), { capture: true });
    lifetime.listen(canvas, 'pointermove', (event) => this.#move(event));
    lifetime.listen(canvas, 'pointerup', (event) => this.#up(event));
    lifetime.listen(canvas, 'pointercancel', () => this.cancel());
    lifetime.listen(canvas, 'pointerleave', () => this.activeTool()?.hover?.(null));
    // Double-click on the mesh: orbit around the clicked point from the same distance.
    lifetime.listen(canvas, 'dblclick', (event) => {
      const { x, y } = this.#position(event);
      const hit = this.picker.pick(x, y);
      if (hit) viewer.focusOn(hit.point);
    });
  }

  get active() {
    return this.#active !== null;
  }

  #position(event) {
    return this.viewer.canvasPoint(event.clientX, event.clientY);
  }

  #down(event) {
    if (this.#handingOver) return;
    if (this.#active && event.pointerId !== this.#active.pointerId) {
      this.#handOverToCamera();
      return;
    }
    if (event.button !== 0 || this.#active) return;
    const tool = this.activeTool();
    if (!tool) return;
    const { x, y } = this.#position(event);
    const hit = this.picker.pick(x, y);
    if (!tool.wantsGesture(hit, event)) return;
    event.stopImmediatePropagation();
    event.preventDefault();
    this.viewer.canvas.setPointerCapture(event.pointerId);
    this.viewer.canvas.focus({ preventScroll: true });
    this.#active = { tool, pointerId: event.pointerId, last: event };
    tool.start({ x, y, hit, event });
  }

  #move(event) {
    const { x, y } = this.#position(event);
    if (!this.#active) {
      const tool = this.activeTool();
      if (tool?.hover && event.buttons === 0) tool.hover({ x, y, hit: this.picker.pick(x, y) });
      return;
    }
    if (event.pointerId !== this.#active.pointerId) return;
    this.#active.last = event;
    this.#active.tool.move({ x, y, event });
  }

  #up(event) {
    if (!this.#active || event.pointerId !== this.#active.pointerId) return;
    const { tool } = this.#active;
    this.#active = null;
    this.viewer.canvas.releasePointerCapture(event.pointerId);
    tool.end({ ...this.#position(event), event });
  }

  #handOverToCamera() {
    const { pointerId, last } = this.#active;
    this.cancel();
    const canvas = this.viewer.canvas;
    if (canvas.hasPointerCapture(pointerId)) canvas.releasePointerCapture(pointerId);
    const { clientX, clientY, screenX, screenY, pointerType, isPrimary } = last;
    const init = { pointerId, pointerType, isPrimary, clientX, clientY, screenX, screenY, button: 0, buttons: 1, bubbles: true };
    this.#handingOver = true;
    try {
      canvas.dispatchEvent(new PointerEvent('pointerdown', init));
    } finally {
      this.#handingOver = false;
    }
  }

  /** Esc or a lost pointer: the tool drops its gesture. */
  cancel() {
    if (!this.#active) return false;
    const { tool } = this.#active;
    this.#active = null;
    tool.cancel();
    return true;
  }
}
