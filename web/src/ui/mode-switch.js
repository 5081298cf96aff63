// Deform / Flatten tabs at the top of the side panel. Flatten mode shows the
// Flatten panel and the 2D pattern view beside the 3D one; only the tools
// that make sense for a pattern (brush selection, arrows) stay available.
import { FLATTEN_MODE_TOOLS } from '../tools/tool-registry.js';
import { h } from './dom.js';

const MODES = [
  ['deform', 'Deform', 'Stretch, thicken, shear, rotate or twist part of the mesh'],
  ['flatten', 'Flatten', 'Flatten an open patch into a garment pattern with directed shrinkage'],
];

// A tab list as the ARIA pattern has it: one Tab stop (the selected tab),
// the arrow keys, Home and End move between the tabs and select them; each
// tab controls its mode's panel (modePanel: role=tabpanel), which a screen
// reader can move to from it.

/** The id of mode `mode`'s tab panel. */
export const modePanelId = (mode) => `mode-panel-${mode}`;

/** Mode `mode`'s sections as its tab panel (shown while the mode is on: the caller's showWhen). */
export function modePanel(mode, ...sections) {
  return h('div', { id: modePanelId(mode), role: 'tabpanel', 'aria-labelledby': `mode-tab-${mode}` }, sections);
}
const ARROWS = { ArrowLeft: -1, ArrowUp: -1, ArrowRight: 1, ArrowDown: 1 };

export function modeSwitch({ settings, app }) {
  settings.defineRule('mode', undefined, (mode) => (MODES.some(([known]) => known === mode) ? mode : undefined));
  const tabs = MODES.map(([mode, label, title]) => h('button', {
    className: 'mode-tab',
    role: 'tab',
    id: `mode-tab-${mode}`,
    'aria-controls': modePanelId(mode),
    title,
    'data-testid': `mode-${mode}`,
    onclick: () => settings.update('mode', mode),
    onkeydown: (event) => {
      const here = MODES.findIndex(([m]) => m === mode);
      let next = null;
      if (event.key in ARROWS) next = (here + ARROWS[event.key] + MODES.length) % MODES.length;
      else if (event.key === 'Home') next = 0;
      else if (event.key === 'End') next = MODES.length - 1;
      if (next === null) return;
      event.preventDefault();
      settings.update('mode', MODES[next][0]);
      tabs[next].focus();
    },
  }, label));
  const sync = () => {
    const mode = settings.values.mode;
    tabs.forEach((tab, index) => {
      const selected = MODES[index][0] === mode;
      tab.setAttribute('aria-selected', String(selected));
      tab.tabIndex = selected ? 0 : -1;
    });
    app.classList.toggle('mode-flatten', mode === 'flatten');
    if (mode === 'flatten' && !FLATTEN_MODE_TOOLS.includes(settings.values.tool)) settings.update('tool', 'select');
  };
  settings.on('change', ({ section }) => section === 'mode' && sync());
  sync();
  return h('div', { className: 'mode-switch', role: 'tablist', 'aria-label': 'Mode' }, tabs);
}
