// The amount of a transform drag, shown beside the pointer while dragging
// (×1.35, 20°), as Blender does: the same value the drag writes into the
// panel's field and the edit commits. Removed when the drag ends.
import { h } from '../ui/dom.js';

// Room between the pointer and the readout, and from the view's edges (px).
const OFFSET = 18;

export class DragReadout {
  constructor(viewer) {
    this.viewer = viewer;
    this.element = h('div', { className: 'drag-readout', 'data-testid': 'drag-readout', 'aria-hidden': 'true' });
  }

  /** Shows `text` near canvas pixel (x, y). */
  show(x, y, text) {
    const element = this.element;
    if (!element.isConnected) this.viewer.container.append(element);
    element.textContent = text;
    const width = this.viewer.canvas.clientWidth;
    const left = Math.min(x + OFFSET, width - element.offsetWidth - 4);
    const top = y - OFFSET - element.offsetHeight;
    Object.assign(element.style, { left: `${Math.max(4, left)}px`, top: `${top < 4 ? y + OFFSET : top}px` });
  }

  hide() {
    this.element.remove();
  }
}

/** The amount of a drag's op in the words of the tool that made it. */
export function dragAmountText(toolId, op) {
  if (op.move) return `move ${Math.hypot(...op.move).toPrecision(3)}`;
  const { scale, shear, rotate, twist } = op.transform;
  if (twist) return `${twist.degreesPerUnit}° per unit`;
  if (rotate) return `${rotate.degrees}°`;
  if (shear !== undefined) return `shear ${shear}`;
  return toolId === 'thicken' ? `×${scale[1]} across` : `×${scale[0]}`;
}
