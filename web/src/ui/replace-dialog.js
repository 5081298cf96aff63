// Asked before the Open… picker or a drop replaces the edits made: opening a
// mesh or saved edits starts a new document, which Undo cannot take back.
// The choices: save the edits first (the Save edits file) and open, open
// anyway, or keep working (the default, and Esc). A modal <dialog>, as the
// shortcut overlay: focus moves into it and stays there until it closes.
import { h } from './dom.js';

export function replaceDialog(root) {
  // Numbered when another modeller holds it (claimUniqueIds, full-ui.js).
  const id = 'replace-dialog';
  const text = h('p', { id: `${id}-text` });
  const choice = (value, label, className = 'button') =>
    h('button', { className, type: 'submit', value, 'data-testid': `replace-${value}` }, label);
  const cancel = choice('cancel', 'Keep working');
  const dialog = h('dialog', {
    className: 'modal-dialog replace-dialog',
    'data-testid': 'replace-dialog',
    'aria-labelledby': `${id}-title`,
    'aria-describedby': `${id}-text`,
  },
  h('form', { method: 'dialog' },
    h('h2', { id: `${id}-title` }, 'Replace the edits?'),
    text,
    h('div', { className: 'row' }, choice('save', 'Save edits, then open', 'button button-primary'), choice('open', 'Open without saving'), cancel)));
  root.append(dialog);

  /** Resolves 'save', 'open' or 'cancel' (Esc too), for a replacement `text` describes. */
  function ask(message) {
    text.textContent = message;
    dialog.returnValue = '';
    dialog.showModal();
    cancel.focus();
    return new Promise((resolve) => {
      dialog.addEventListener('close', () => resolve(dialog.returnValue || 'cancel'), { once: true });
    });
  }
  return { ask, element: dialog };
}
