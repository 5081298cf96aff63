// Undo / redo buttons (Ctrl+Z, Ctrl+Shift+Z), labelled with the step they undo.
import { h } from './dom.js';

export function historyButtons({ api, editor }) {
  const undo = h('button', { className: 'button', 'data-testid': 'undo', disabled: true, onclick: () => api.undo() }, 'Undo');
  const redo = h('button', { className: 'button', 'data-testid': 'redo', disabled: true, onclick: () => api.redo() }, 'Redo');
  // While a solve runs the buttons wait (as the keys do: editor.undo()).
  let state = { canUndo: false, canRedo: false };
  let busy = false;
  const sync = () => {
    undo.disabled = !state.canUndo || busy;
    redo.disabled = !state.canRedo || busy;
  };
  editor.on('history', (next) => {
    state = next;
    const { canUndo, canRedo, undoLabel, redoLabel } = next;
    undo.title = canUndo ? `Undo ${undoLabel} (Ctrl+Z)` : 'Nothing to undo';
    redo.title = canRedo ? `Redo ${redoLabel} (Ctrl+Shift+Z)` : 'Nothing to redo';
    sync();
  });
  editor.on('busy', (now) => {
    busy = now;
    sync();
  });
  return h('div', { className: 'row history' }, undo, redo);
}
