// On narrow screens (narrow-layout.css) the side panel is a bottom sheet
// under the view(s); this button in its header folds it down to that header,
// giving the view the height, and opens it again. On wide screens the button
// is not shown and the panel is always open.
import { h } from './dom.js';

export function panelSheetToggle(sidePanel) {
  const button = h('button', {
    className: 'button sheet-toggle',
    type: 'button',
    'data-testid': 'sheet-toggle',
    onclick: () => setOpen(sidePanel.classList.contains('sheet-closed')),
  });
  const setOpen = (open) => {
    sidePanel.classList.toggle('sheet-closed', !open);
    button.setAttribute('aria-expanded', String(open));
    button.textContent = open ? 'Hide panel' : 'Show panel';
    button.title = open ? 'Fold the panel down to give the view more room' : 'Open the tools and settings';
  };
  setOpen(true);
  sidePanel.querySelector('.brand').append(button);
  return button;
}
