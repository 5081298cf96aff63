// The amount of a transform drag, shown beside the pointer while dragging
// (×1.35, 20°), as Blender does: the same value the drag writes into the
// panel's field and the edit commits. Removed when the drag ends.
import { h } from '../ui/dom.js';

// Room between the pointer and the readout (px).
const OFFSET = 18;
// A readout is at most about this wide and high (px): "12.5° per unit" in
// the overlay's font. Nearer than that to the view's right or top edge it
// goes to the pointer's other side.
const ROOM_X = 140;
const ROOM_Y = 40;

export class DragReadout {
  constructor(viewer) {
    this.viewer = viewer;
    this.element = h('div', { className: 'drag-readout', 'data-testid': 'drag-readout', 'aria-hidden': 'true' });
  }

  /**
   * Shows `text` near canvas pixel (x, y): above and to the right of it, or
   * on the pointer's other side near the view's right or top edge. Placed by
   * the pointer's position and CSS translations only, never by reading the
   * readout's size: that read laid the page out again at every pointer move
   * of a drag (after the panel's field and this text had changed): 184 ms of
   * the page's thread in a 2 s drag at 50k vertices (its CPU profile, 92
   * moves).
   */
  show(x, y, text) {
    const element = this.element;
    if (!element.isConnected) this.viewer.container.append(element);
    element.textContent = text;
    const leftOfPointer = x + OFFSET + ROOM_X > this.viewer.width;
    const belowPointer = y - OFFSET - ROOM_Y < 0;
    Object.assign(element.style, {
      left: `${leftOfPointer ? x - OFFSET : x + OFFSET}px`,
      top: `${belowPointer ? y + OFFSET : y - OFFSET}px`,
      transform: `translate(${leftOfPointer ? '-100%' : '0'}, ${belowPointer ? '0' : '-100%'})`,
    });
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
