// The DOM of one modeller, built inside its container (no ids: several
// modellers may share a page). 'full': the standalone site's layout (side
// panel, viewport with messages and drop overlay, pattern pane, status bar;
// styled by ui/styles.css). 'none': the viewport alone, styled inline so an
// embedder needs no stylesheet. `element` is what was added to the container.
import { h } from '../ui/dom.js';

export const UI_MODES = ['full', 'none'];

export function buildLayout(container, ui) {
  if (ui === 'none') {
    const viewport = h('div', {
      className: 'anisoform-viewport',
      style: { position: 'relative', overflow: 'hidden', width: '100%', height: '100%' },
    });
    container.append(viewport);
    return { element: viewport, root: viewport, viewport };
  }
  const sidePanel = h('aside', { className: 'side-panel', 'aria-label': 'Tools and settings' },
    h('header', { className: 'brand' },
      h('h1', {}, 'Anisoform'),
      h('p', {}, 'Select a region, pick a direction, drag to deform.')));
  const message = (kind, role) => h('div', { className: `message message-${kind}`, 'data-testid': kind, role, hidden: true });
  const dropOverlay = h('div', { className: 'drop-overlay', 'data-testid': 'drop-overlay', hidden: true }, 'Drop a mesh file (OBJ, PLY, STL, OFF, GLB)');
  // Most important first: where the view is short (a phone's, with the
  // heat-map legend shown) only the first lines show, and a load's notice
  // above a flattening's warning left the warning a strip with no text.
  const viewport = h('main', { className: 'viewport' },
    h('div', { className: 'viewport-messages' }, message('error', 'alert'), message('warning', 'status'), message('notice', 'status')),
    dropOverlay);
  const patternPane = h('section', {
    className: 'pattern-pane', 'data-testid': 'pattern-view', 'aria-label': 'Flattened pattern', hidden: true,
  });
  const statusBar = h('footer', { className: 'status-bar', 'aria-label': 'Status' });
  const root = h('div', { className: 'app' }, sidePanel, viewport, patternPane, statusBar);
  // The narrow layout follows this frame's width, not the window's
  // (narrow-layout.css): a 400 px container on a wide page is laid out as a
  // phone, and the .app grid inside can change its columns (a container
  // query styles the container's descendants only).
  const frame = h('div', { className: 'app-frame' }, root);
  container.append(frame);
  return { element: frame, root, viewport, sidePanel, dropOverlay, patternPane, statusBar };
}
