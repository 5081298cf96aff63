// Undo / redo buttons (Ctrl+Z, Ctrl+Shift+Z), labelled with the step they undo.
import { h } from './dom.js';

export function historyButtons({ api, editor }) {
  const undo = h('button', { className: 'button', 'data-testid': 'undo', disabled: true, onclick: () => api.undo() }, 'Undo');
  const redo = h('button', { className: 'button', 'data-testid': 'redo', disabled: true, onclick: () => api.redo() }, 'Redo');
  editor.on('history', ({ canUndo, canRedo, undoLabel, redoLabel }) => {
    undo.disabled = !canUndo;
    redo.disabled = !canRedo;
    undo.title = canUndo ? `Undo ${undoLabel} (Ctrl+Z)` : 'Nothing to undo';
    redo.title = canRedo ? `Redo ${redoLabel} (Ctrl+Shift+Z)` : 'Nothing to redo';
  });
  return h('div', { className: 'row history' }, undo, redo);
}
