// Undo / redo buttons (Ctrl+Z, Ctrl+Shift+Z), labelled with the step they
// undo; off (focusable-disabled.js) while there is nothing to take back or
// do again, so that the keyboard's focus stays on them.
import { h } from './dom.js';
import { setOff, whenOn } from './focusable-disabled.js';

export function historyButtons({ api, editor }) {
  const undo = h('button', { className: 'button', 'data-testid': 'undo', 'aria-disabled': 'true', onclick: whenOn(() => api.undo()) }, 'Undo');
  const redo = h('button', { className: 'button', 'data-testid': 'redo', 'aria-disabled': 'true', onclick: whenOn(() => api.redo()) }, 'Redo');
  // While a solve runs the buttons wait (as the keys do: editor.undo()).
  let state = { canUndo: false, canRedo: false };
  let busy = false;
  const sync = () => {
    setOff(undo, !state.canUndo || busy);
    setOff(redo, !state.canRedo || busy);
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
