// Selection commands: all, clear, invert, grow and shrink by one ring; each
// is one undo step. All and Clear are the core's regions (api.select); grow,
// shrink and invert work on the page's weights (selection-morphology.js).
import { growSelection, invertSelection, shrinkSelection } from '../selection/selection-morphology.js';
import { formatCount } from '../shared/number-format.js';
import { h, section } from './dom.js';
import { setOff, whenOn } from './focusable-disabled.js';

/** What is selected, in words (the panel's line; the announcer says it too). */
export function selectionText(document) {
  return document.selectionCount === 0
    ? 'Nothing selected: edits apply to the whole mesh.'
    : `${formatCount(document.selectionCount)} of ${formatCount(document.vertexCount)} vertices selected`;
}

export function selectionPanel({ api, editor }) {
  const count = h('p', { className: 'selection-count' });
  // The editor reports failures itself (the banner); a rejected select() needs no second word.
  const withDocument = (action) => () => editor.document && Promise.resolve(action(editor.document)).catch(() => {});
  // Off while a committed solve runs, as Apply and Undo are: All and Clear
  // waited behind the solve while Invert, Grow and Shrink acted at once, so
  // Clear then Invert ended as Invert then Clear.
  const buttons = [];
  const button = (label, testId, action) => {
    const element = h('button', { className: 'button', 'data-testid': testId, onclick: whenOn(withDocument(action)) }, label);
    buttons.push(element);
    return element;
  };
  editor.on('busy', (busy) => buttons.forEach((element) => setOff(element, busy)));

  const sync = () => (count.textContent = editor.document ? selectionText(editor.document) : '');
  editor.on('selection', ({ live }) => !live && sync());
  editor.on('mesh', sync);

  return section(
    'Selection',
    count,
    h('div', { className: 'button-grid' },
      button('All', 'select-all', () => api.select({ all: true })),
      button('Clear', 'select-clear', () => api.select({ vertices: [] })),
      button('Invert', 'select-invert', (d) => editor.setSelection(invertSelection(d.selection), 'Invert selection')),
      button('Grow', 'select-grow', (d) => editor.setSelection(growSelection(d.selection, d.adjacency), 'Grow selection')),
      button('Shrink', 'select-shrink', (d) => editor.setSelection(shrinkSelection(d.selection, d.adjacency), 'Shrink selection')),
    ),
  );
}
