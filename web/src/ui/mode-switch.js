// Deform / Flatten tabs at the top of the side panel. Flatten mode shows the
// Flatten panel and the 2D pattern view beside the 3D one; only the tools
// that make sense for a pattern (brush selection, arrows) stay available.
import { FLATTEN_MODE_TOOLS } from '../tools/tool-registry.js';
import { h } from './dom.js';

const MODES = [
  ['deform', 'Deform', 'Stretch, thicken, shear, rotate or twist part of the mesh'],
  ['flatten', 'Flatten', 'Flatten an open patch into a garment pattern with directed shrinkage'],
];

export function modeSwitch({ settings, app }) {
  const tabs = MODES.map(([mode, label, title]) => h('button', {
    className: 'mode-tab',
    role: 'tab',
    title,
    'data-testid': `mode-${mode}`,
    onclick: () => settings.update('mode', mode),
  }, label));
  const sync = () => {
    const mode = settings.values.mode;
    tabs.forEach((tab, index) => tab.setAttribute('aria-selected', String(MODES[index][0] === mode)));
    app.classList.toggle('mode-flatten', mode === 'flatten');
    if (mode === 'flatten' && !FLATTEN_MODE_TOOLS.includes(settings.values.tool)) settings.update('tool', 'select');
  };
  settings.on('change', ({ section }) => section === 'mode' && sync());
  sync();
  return h('div', { className: 'mode-switch', role: 'tablist', 'aria-label': 'Mode' }, tabs);
}
