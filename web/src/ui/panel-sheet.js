// On narrow screens (narrow-layout.css) the side panel is a bottom sheet
// under the view(s); this button in its header folds it down to that header,
// giving the view the height, and opens it again. On wide screens the button
// is not shown and the panel is always open.
import { h } from './dom.js';

export function panelSheetToggle(sidePanel, lifetime) {
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
  const header = sidePanel.querySelector('.brand');
  header.append(button);
  // The header sticks to the sheet's top (narrow-layout.css): a control
  // focused by Tab scrolled to the top edge sat under it at 200 % and 400 %
  // zoom. Its height (it wraps when narrow) is the sheet's scroll padding.
  const measure = new ResizeObserver(() => sidePanel.style.setProperty('--sheet-header-height', `${Math.ceil(header.getBoundingClientRect().height)}px`));
  measure.observe(header);
  lifetime.defer(() => measure.disconnect());
  return button;
}
