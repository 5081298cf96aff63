// Keyboard shortcuts: Ctrl/Cmd+Z undo, Ctrl/Cmd+Shift+Z (or Ctrl+Y) redo,
// Esc cancels a live edit, F or Home frames the whole mesh. Ignored while
// typing in a field, where those keys belong to the field.
// `target` decides whose keys they are: the modeller's root element (keys
// pressed while focus is inside it: an embedded modeller leaves the rest of
// the page's keys alone) or the window (the standalone site, which is the
// whole page).
export function installKeyboardShortcuts(target, lifetime, { undo, redo, cancel, frame }) {
  lifetime.listen(target, 'keydown', (event) => {
    const typing = event.target instanceof HTMLInputElement || event.target instanceof HTMLSelectElement
      || event.target instanceof HTMLTextAreaElement || event.target?.isContentEditable;
    if (event.key === 'Escape') {
      if (cancel()) event.preventDefault();
      return;
    }
    if (typing) return;
    const modified = event.ctrlKey || event.metaKey || event.altKey;
    if (!modified && (event.key === 'Home' || event.key.toLowerCase() === 'f')) {
      event.preventDefault();
      frame();
      return;
    }
    if (!(event.ctrlKey || event.metaKey)) return;
    const key = event.key.toLowerCase();
    if (key === 'z' && !event.shiftKey) {
      event.preventDefault();
      undo();
    } else if ((key === 'z' && event.shiftKey) || key === 'y') {
      event.preventDefault();
      redo();
    }
  });
}
