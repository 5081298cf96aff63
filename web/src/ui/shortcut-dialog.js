// The keyboard shortcut overlay (the ? key): a modal dialog listing every
// key (interaction/shortcut-list.js). The browser's <dialog> gives it the
// dialog role, moves focus into it, keeps focus there and closes it on Esc.
import { shortcutRows } from '../interaction/shortcut-list.js';
import { h } from './dom.js';

export function shortcutDialog(root, { tools }) {
  const close = h('button', { className: 'button', type: 'button', onclick: () => dialog.close() }, 'Close');
  const dialog = h('dialog', { className: 'modal-dialog shortcut-dialog', 'data-testid': 'shortcut-dialog', 'aria-label': 'Keyboard shortcuts' },
    h('h2', {}, 'Keyboard shortcuts'),
    h('table', {},
      h('tbody', {}, shortcutRows(tools).map(([keys, action]) => h('tr', {}, h('th', { scope: 'row' }, keys), h('td', {}, action))))),
    h('div', { className: 'row' }, close));
  root.append(dialog);
  return dialog;
}
