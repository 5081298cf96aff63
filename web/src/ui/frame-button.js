// The Frame button over the 3D viewport: fits the camera to the whole mesh
// (the same as the F and Home keys).
import { h } from './dom.js';

export function frameButton(viewport, { api }) {
  const button = h('button', {
    className: 'button viewport-frame',
    type: 'button',
    title: 'Frame the whole mesh (F or Home; double-click the mesh to orbit around a point)',
    'aria-label': 'Frame mesh',
    'data-testid': 'frame-mesh',
    onclick: () => api.frame(),
  }, 'Frame');
  viewport.append(button);
  return button;
}
