// Keyboard shortcuts: Ctrl/Cmd+Z undo, Ctrl/Cmd+Shift+Z (or Ctrl+Y) redo,
// Esc cancels a live edit or a committed solve, F or Home frames the whole mesh. Ignored while
// typing in a field, where those keys belong to the field, and inside an
// open dialog (the shortcut overlay), which has the keys to itself. The
// full UI's editing keys: editing-keys.js; the list of all: shortcut-list.js.
// `target` decides whose keys they are: the modeller's root element (keys
// pressed while focus is inside it: an embedded modeller leaves the rest of
// the page's keys alone) or the window (the standalone site, which is the
// whole page).
export function installKeyboardShortcuts(target, lifetime, { undo, redo, cancel, frame }) {
  lifetime.listen(target, 'keydown', (event) => {
    if (event.target instanceof Element && event.target.closest('dialog[open]')) return;
    if (event.key === 'Escape') {
      if (cancel()) event.preventDefault();
      return;
    }
    if (isTyping(event)) return;
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

// Inputs that take no typing: a key pressed on one (after a click on an
// Edits-list checkbox, say) is the modeller's.
const KEYLESS_INPUTS = new Set(['checkbox', 'radio', 'button', 'submit', 'reset', 'color', 'file']);

/** Whether the key goes to a text field, select or editable element rather than to the modeller. */
export function isTyping(event) {
  const target = event.target;
  return (target instanceof HTMLInputElement && !KEYLESS_INPUTS.has(target.type)) || target instanceof HTMLSelectElement
    || target instanceof HTMLTextAreaElement || target?.isContentEditable === true;
}
