// The pattern files' scale in the Flatten panel: the mesh's unit (guessed by
// the core from the mesh's size, guess_model_unit in op.h, and said to be a
// guess; or chosen; or a custom number of millimetres per unit) and the
// physical size of the pattern it gives, so that a 4 mm torso is seen before
// it is printed.
import { h } from './dom.js';
import { numberField, selectField, showWhen } from './fields.js';

const UNIT_NAMES = { m: 'metres', cm: 'centimetres', mm: 'millimetres', in: 'inches' };
const MM_PER_UNIT = { m: 1000, cm: 10, mm: 1, in: 25.4 };

/** Millimetres per model unit for the flatten settings and the loaded mesh's info. */
export function mmPerUnitOf(flatten, info) {
  if (flatten.unit === 'custom') return flatten.mmPerUnit;
  if (flatten.unit === 'guess') return info?.unitGuess?.mmPerUnit ?? 1;
  return MM_PER_UNIT[flatten.unit];
}

/** The pattern's outline box in model units: [width, height] (the box the pattern files are drawn in). */
export function patternExtent(pattern) {
  let minU = Infinity, minV = Infinity, maxU = -Infinity, maxV = -Infinity;
  for (const outline of pattern.outlines) {
    for (const vertex of outline) {
      const u = pattern.uv[2 * vertex], v = pattern.uv[2 * vertex + 1];
      minU = Math.min(minU, u); maxU = Math.max(maxU, u);
      minV = Math.min(minV, v); maxV = Math.max(maxV, v);
    }
  }
  return maxU >= minU ? [maxU - minU, maxV - minV] : [0, 0];
}

export function patternScale({ editor, settings }) {
  const unitField = selectField(settings, 'flatten', {
    key: 'unit',
    label: 'Mesh unit',
    options: [['guess', 'Guessed'], ['m', 'Metres'], ['cm', 'Centimetres'], ['mm', 'Millimetres'], ['in', 'Inches'], ['custom', 'Custom (mm per unit)']],
  });
  const guessOption = unitField.querySelector('option[value=guess]');
  const custom = showWhen(settings, 'flatten',
    // The core's range (limits.h kMinMmPerUnit..kMaxMmPerUnit): a value
    // outside it showed a negative or zero pattern size until an export refused it.
    numberField(settings, 'flatten', { key: 'mmPerUnit', label: 'mm per unit', step: 1, min: 0.001, max: 1e6 }),
    (f) => f.unit === 'custom');
  const note = h('p', { className: 'hint', 'data-testid': 'pattern-unit-note' });
  const size = h('p', { className: 'hint', 'data-testid': 'pattern-size' });

  const sync = () => {
    const info = editor.document?.info;
    const guess = info?.unitGuess;
    guessOption.textContent = guess ? `Guessed: ${UNIT_NAMES[guess.name]}` : 'Guessed';
    const flatten = settings.values.flatten;
    if (flatten.unit === 'guess' && info) {
      const side = Math.max(...info.bbox.max.map((max, axis) => max - info.bbox.min[axis]));
      note.textContent = `Guessed from the mesh's size (largest side ${formatNumber(side)} units): ${UNIT_NAMES[guess.name]}. `
        + 'Choose the unit if the mesh was modelled in another.';
    } else {
      note.textContent = '';
    }
    note.hidden = note.textContent === '';
    const pattern = editor.pattern;
    if (!pattern) {
      size.textContent = 'Pattern size: flatten first.';
      delete size.dataset.widthMm;
      delete size.dataset.heightMm;
      return;
    }
    const scale = mmPerUnitOf(flatten, info);
    const [width, height] = patternExtent(pattern).map((extent) => extent * scale);
    size.dataset.widthMm = String(width);
    size.dataset.heightMm = String(height);
    // In inches for a mesh in inches (the files are in mm, said beside it).
    size.textContent = flatten.unit === 'in'
      ? `Pattern size: ${formatNumber(width / 25.4)} in × ${formatNumber(height / 25.4)} in (${formatMm(width)} × ${formatMm(height)}; 1 unit = 25.4 mm)`
      : `Pattern size: ${formatMm(width)} × ${formatMm(height)} (1 unit = ${formatNumber(scale)} mm)`;
  };
  editor.on('mesh', sync);
  editor.on('pattern', sync);
  settings.on('change', ({ section }) => section === 'flatten' && sync());
  sync();
  return h('div', { className: 'pattern-scale' }, unitField, custom, note, size);
}

function formatMm(mm) {
  if (mm >= 1000) return `${(mm / 1000).toFixed(2)} m`;
  if (mm >= 100) return `${(mm / 10).toFixed(1)} cm`;
  if (mm >= 1) return `${mm.toFixed(mm >= 10 ? 1 : 2)} mm`;
  // Three significant digits under a millimetre, as the files are written
  // (pattern_export.h): a pattern read at a wrong unit said "0.00 mm".
  return `${formatNumber(mm)} mm`;
}

function formatNumber(value) {
  return Number(value.toPrecision(3)).toString();
}
