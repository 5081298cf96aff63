// Tool buttons and the active tool's options: brush settings and selecting
// the brush region at the view centre (no painting) for Select, numeric
// amounts with Apply for the transforms, the arrow list for Arrows.
import { TOOL_KEYS } from '../interaction/shortcut-list.js';
import { FLATTEN_MODE_TOOLS } from '../tools/tool-registry.js';
import { h, section } from './dom.js';
import { setOff, whenOn } from './focusable-disabled.js';
import { numberField, selectField, showWhen, vectorField } from './fields.js';

export function toolPanel({ editor, settings, tools, reportError, selectRegion }) {
  settings.defineRule('tool', undefined, (id) => (tools.has(id) ? id : undefined));
  const buttons = [...tools.values()].map((tool) =>
    h('button', {
      className: 'tool-button',
      'data-testid': `tool-${tool.id}`,
      'aria-pressed': 'false',
      'aria-keyshortcuts': TOOL_KEYS[tool.id].toUpperCase(),
      title: `${tool.hint} (key ${TOOL_KEYS[tool.id].toUpperCase()})`,
      onclick: () => settings.update('tool', tool.id),
    }, tool.label),
  );
  const options = new Map([...tools.values()].map((tool) => [tool.id, toolOptions(tool, { editor, settings, reportError, selectRegion })]));
  const hint = h('p', { className: 'hint tool-hint' });
  const optionsHost = h('div', { className: 'tool-options' }, [...options.values()]);

  const sync = () => {
    const active = settings.values.tool;
    const flattening = settings.values.mode === 'flatten';
    buttons.forEach((button, index) => {
      const id = [...tools.keys()][index];
      button.setAttribute('aria-pressed', String(id === active));
      button.hidden = flattening && !FLATTEN_MODE_TOOLS.includes(id);
    });
    for (const [id, element] of options) element.hidden = id !== active;
    hint.textContent = tools.get(active)?.hint ?? '';
  };
  settings.on('change', ({ section: name }) => (name === 'tool' || name === 'mode') && sync());
  sync();
  return section('Tool', h('div', { className: 'tool-grid' }, buttons), hint, optionsHost);
}

function toolOptions(tool, { editor, settings, reportError, selectRegion }) {
  if (tool.id === 'select') {
    return h('div', {},
      numberField(settings, 'brush', { key: 'radiusPercent', label: 'Radius %', min: 0.5, max: 100, step: 0.5 }),
      numberField(settings, 'brush', { key: 'softnessPercent', label: 'Soft edge %', min: 0, max: 100, step: 5 }),
      selectField(settings, 'brush', { key: 'mode', label: 'Mode', options: [['add', 'Add'], ['subtract', 'Subtract']] }),
      // Painting is always with the ball the cursor shows: the shape is the view-centre selection's.
      selectField(settings, 'brush', { key: 'region', label: 'At view centre', options: [['sphere', 'Sphere'], ['box', 'Box']] }),
      h('div', { className: 'row' },
        h('button', {
          className: 'button',
          'data-testid': 'select-region-centre',
          'aria-keyshortcuts': 'C',
          title: 'Select the region (radius as the brush) at the surface in the middle of the view, without painting (key C)',
          onclick: () => selectRegion(),
        }, 'Select at view centre')),
    );
  }
  if (tool.id === 'arrows') {
    const count = h('span', {});
    const sync = () => (count.textContent = `${settings.values.arrows.length} arrow(s) placed`);
    settings.on('change', ({ section: name }) => name === 'arrows' && sync());
    sync();
    return h('div', { className: 'row' }, count,
      h('button', { className: 'button', onclick: () => settings.update('arrows', []) }, 'Clear arrows'));
  }
  const fields = tool.fields.map((field) => {
    let element;
    if (field.options) element = selectField(settings, tool.id, field);
    else if (field.vector) element = vectorField(settings, tool.id, field);
    else element = numberField(settings, tool.id, field);
    return field.showWhen ? showWhen(settings, tool.id, element, field.showWhen) : element;
  });
  // A refusal (no direction yet, a method without amounts) says what to do;
  // a solver failure is reported by the editor, and not twice.
  const apply = h('button', {
    className: 'button button-primary',
    'data-testid': `apply-${tool.id}`,
    onclick: whenOn(() => Promise.resolve()
      .then(() => tool.apply())
      .catch((error) => reportError(error, `${tool.label} was not applied`))),
  }, 'Apply');
  // One commit at a time: clicks during a solve would stack edits the user
  // did not see the first of.
  editor.on('busy', (busy) => setOff(apply, busy));
  return h('div', {}, fields, h('div', { className: 'row' }, apply));
}
