// Flatten mode's side panel: which patch (the whole open mesh or the
// selection), the wanted direction (global axis or arrows placed on the
// surface, each arrow with its own compression if wanted), the wanted
// stretch along / across it, the garment-CAD baseline for comparison, the
// run button with the measured result, the pattern's unit and physical size
// (pattern-scale.js), and SVG / DXF export of the pattern.
import { downloadBytes } from '../io/download.js';
import { flattenDirectionFromSettings } from '../tools/direction-source.js';
import { formatPercent } from '../shared/number-format.js';
import { decimalInput, parseDecimal } from './decimal-input.js';
import { h, section } from './dom.js';
import { mmPerUnitOf, patternScale } from './pattern-scale.js';
import { setOff, whenOn } from './focusable-disabled.js';
import { checkboxField, numberField, selectField, showWhen, vectorField } from './fields.js';

export function flattenPanel({ api, editor, settings, reportError }) {
  const run = h('button', {
    className: 'button button-primary',
    'data-testid': 'flatten-run',
    onclick: whenOn(() => flattenFromSettings({ api, editor, settings, reportError })),
  }, 'Flatten');
  const metrics = h('div', { className: 'flatten-metrics', 'data-testid': 'flatten-metrics' });
  editor.on('pattern', (pattern) => showMetrics(metrics, pattern));
  editor.on('busy', (busy) => setOff(run, busy));
  showMetrics(metrics, null);

  const exportButton = (format) => h('button', {
    className: 'button',
    'data-testid': `export-${format}`,
    disabled: true,
    onclick: async () => {
      const mmPerUnit = mmPerUnitOf(settings.values.flatten, editor.document?.info);
      const bytes = await api.exportPattern(format, { mmPerUnit }).catch((error) => {
        reportError(error);
        return null;
      });
      if (!bytes) return;
      const baseName = (editor.document?.name ?? 'pattern').replace(/\.[^.]+$/, '');
      downloadBytes(bytes, `${baseName}-pattern.${format}`, format === 'svg' ? 'image/svg+xml' : 'application/dxf');
    },
  }, format.toUpperCase());
  const exports = [exportButton('svg'), exportButton('dxf')];
  // A pattern made with other settings than the panel's now is out of date:
  // said, and not exported (its file used to carry the old amounts while
  // the panel showed the new ones).
  const stale = h('p', { className: 'hint pattern-stale', 'data-testid': 'pattern-stale', hidden: true },
    'The settings changed since this pattern was made: Flatten again to update it (export waits until then).');
  // (A pattern the api made with options the panel never showed is not the panel's to judge.)
  let panelMade = false;
  const panelNow = (pattern) => sameFlattenOptions(pattern.options, panelOptionsOrNull(settings.values, editor.document));
  const syncStale = () => {
    const pattern = editor.pattern;
    const outdated = Boolean(pattern) && panelMade && !panelNow(pattern);
    stale.hidden = !outdated;
    exports.forEach((button) => (button.disabled = !pattern || outdated));
  };
  editor.on('pattern', (pattern) => {
    panelMade = Boolean(pattern) && panelNow(pattern);
    syncStale();
  });
  settings.on('change', ({ section }) => (section === 'flatten' || section === 'arrows') && syncStale());

  return section(
    'Flatten',
    selectField(settings, 'flatten', {
      key: 'patch', label: 'Patch', options: [['mesh', 'Whole mesh (open)'], ['selection', 'Selection']],
    }),
    selectField(settings, 'flatten', { key: 'source', label: 'Direction', options: [['global', 'Global axis'], ['arrows', 'Arrows']] }),
    showWhen(settings, 'flatten',
      selectField(settings, 'flatten', {
        key: 'axis', label: 'Axis', options: [['auto', 'Longest side'], ['x', 'X'], ['y', 'Y'], ['z', 'Z'], ['custom', 'Custom']],
      }),
      (f) => f.source === 'global'),
    showWhen(settings, 'flatten', vectorField(settings, 'flatten', { key: 'custom', label: 'Vector' }),
      (f) => f.source === 'global' && f.axis === 'custom'),
    numberField(settings, 'flatten', { key: 'along', label: 'Stretch along', step: 0.01 }),
    numberField(settings, 'flatten', { key: 'across', label: 'Stretch across', step: 0.01 }),
    showWhen(settings, 'flatten', arrowList(settings), (f) => f.source === 'arrows'),
    checkboxField(settings, 'flatten', { key: 'baseline', label: 'Industry baseline (uniform 2D scale)' }),
    // The core's stretch refinement after the paper's ARAP (README,
    // Flattening refinement): off, the pattern shears less and misses the
    // lengths more, which the shear warning offers.
    checkboxField(settings, 'flatten', { key: 'refine', label: 'Refine lengths (off: the paper\'s ARAP result, less shear)' }),
    h('p', { className: 'hint' }, 'Stretch 0.8 = the fabric is cut 20 % shorter along the direction.'),
    h('div', { className: 'row' }, run),
    stale,
    metrics,
    patternScale({ editor, settings }),
    h('div', { className: 'row' }, h('span', { className: 'hint' }, 'Export pattern'), ...exports),
  );
}

/** Runs the flattening the panel describes; refusals and errors reach the banner. */
export function flattenFromSettings({ api, editor, settings, reportError }) {
  const values = settings.values;
  const document = editor.document;
  if (!document) return;
  let direction;
  try {
    direction = flattenDirectionFromSettings(values, document.bounds());
  } catch (error) {
    reportError(error, 'Flatten was not run');
    return;
  }
  // A closed mesh has no boundary to flatten whole: with a part selected,
  // the panel flattens that part and shows Selection as its patch (left at
  // Whole mesh, the user's selection met a refusal that asked for one).
  if (values.flatten.patch === 'mesh' && document.info.boundaryLoops === 0 && document.selectionCount > 0) {
    settings.update('flatten', { patch: 'selection' });
  }
  api.flatten(panelOptions(settings.values, direction))
    .then(() => settings.update('display', { heatMap: 'compression' }))
    .catch(reportError); // the editor has shown its own errors already
}

// The flatten options of the panel's settings, with `direction` resolved.
function panelOptions(values, direction) {
  const options = { compress: [values.flatten.along, values.flatten.across], direction, patch: values.flatten.patch };
  if (values.flatten.baseline) options.baseline = 'uniform';
  if (!values.flatten.refine) options.refine = false;
  return options;
}

// The options Flatten would send now; null when it would be refused (no arrows yet).
function panelOptionsOrNull(values, document) {
  if (!document) return null;
  try {
    return panelOptions(values, flattenDirectionFromSettings(values, document.bounds()));
  } catch {
    return null;
  }
}

// Whether a pattern made with `made` (PatternState's options) is what `now` would make.
function sameFlattenOptions(made, now) {
  if (!now) return false;
  const key = ({ compress, direction, patch = 'mesh', baseline = null, refine = true }) => JSON.stringify({ compress, direction, patch, baseline, refine });
  return key(made) === key(now);
}

// The placed arrows, each with an optional compression of its own (empty =
// the panel's amounts), and a button to remove it.
function arrowList(settings) {
  const list = h('div', { className: 'arrow-list', 'data-testid': 'arrow-list' });
  const amountInput = (index, key, label) => {
    const arrow = settings.values.arrows[index];
    const input = decimalInput({
      placeholder: 'panel', value: arrow[key] ?? '',
      'aria-label': `Arrow ${index + 1} ${label}`,
    });
    input.addEventListener('change', () => {
      const arrows = settings.values.arrows.map((a) => ({ ...a }));
      const value = parseDecimal(input.value);
      if (input.value === '' || !(value > 0)) delete arrows[index][key];
      else arrows[index][key] = value;
      settings.update('arrows', arrows);
    });
    return input;
  };
  const sync = () => {
    const arrows = settings.values.arrows;
    list.replaceChildren(
      arrows.length === 0
        ? h('p', { className: 'hint' }, 'Drag on the surface with the Arrows tool to place directions.')
        : h('p', { className: 'hint' }, 'Per arrow: stretch along, across (empty = the Stretch along and across above).'),
      ...arrows.map((arrow, index) => h('div', { className: 'row arrow-row' },
        h('span', {}, `#${index + 1} v${arrow.vertex}`),
        amountInput(index, 'su', 'stretch along'),
        amountInput(index, 'sv', 'stretch across'),
        h('button', {
          type: 'button',
          className: 'dismiss',
          title: 'Remove this arrow',
          'aria-label': `Remove arrow ${index + 1}`,
          onclick: () => settings.update('arrows', settings.values.arrows.filter((_, i) => i !== index)),
        }, '×'),
      )),
    );
  };
  settings.on('change', ({ section: name }) => name === 'arrows' && sync());
  sync();
  return list;
}

function showMetrics(element, pattern) {
  if (!pattern) {
    element.replaceChildren(h('p', { className: 'hint' }, 'No pattern yet.'));
    return;
  }
  const m = pattern.metrics;
  const row = (label, value, testId) => h('div', { className: 'metric' }, h('span', {}, label), h('b', { 'data-testid': testId }, value));
  element.replaceChildren(
    row('Method', m.method === 'uniform-baseline' ? 'Baseline (uniform)' : 'Anisotropic ARAP', 'metric-method'),
    row('Compression error', `${formatPercent(m.compressionErrorMean)} mean · ${formatPercent(m.compressionErrorMax)} max`, 'metric-compression'),
    row('Cross error', `${formatPercent(m.crossErrorMean)} mean · ${formatPercent(m.crossErrorMax)} max`, 'metric-cross'),
    row('Area distortion', formatPercent(m.areaDistortionMean), 'metric-area'),
    row('Shear', `${m.shearDegreesMean.toFixed(1)}° mean · ${m.shearDegreesMax.toFixed(1)}° max`, 'metric-shear'),
    row('Flipped triangles', String(m.flipped), 'metric-flipped'),
    row('Pieces · outlines', `${m.components} · ${m.boundaryLoops}`, 'metric-pieces'),
    row('Iterations', `${m.iterations}${m.converged ? '' : ' (not converged)'} · ${(1000 * m.seconds).toFixed(0)} ms`, 'metric-iterations'),
  );
}
