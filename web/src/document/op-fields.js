// The fields of the Edits list's selected op (ops-panel.js): its amounts, its
// method and its direction (an ARAP drag's move), each written back with
// api.setParameter (the op and the later ones re-run; a step of the
// history), and previewed live while a number is typed; and its region's
// soft border (api.setRegion). A field left empty, or not a number, is no
// value: the op's own shows again.
import { h } from '../ui/dom.js';
import { decimalInput, parseDecimal } from '../ui/decimal-input.js';
import { METHOD_NAMES, describeEdit } from '../editor/edit-wording.js';
import { transformUsesDirection } from '../tools/direction-source.js';

// The amounts of a transform an op's row offers, as [test id, label, read,
// write], labelled as the tools' panels label them. A Thicken op (a scale
// [1, sv], describeEdit) shows its one amount, as its tool does: "Stretch
// along" beside it read as "thicker" and turned it into a stretch.
const AMOUNTS = [
  ['Stretch along', 'Along ×', (t) => (isThicken(t) ? undefined : t.scale?.[0] ?? t.scale), (t, v) => ({ scale: [v, t.scale?.[1] ?? 1] })],
  ['Stretch across', 'Across ×', (t) => t.scale?.[1], (t, v) => ({ scale: [t.scale?.[0] ?? t.scale ?? 1, v] })],
  ['Thickness', 'Thickness', (t) => t.thickness, (t, v) => ({ thickness: v })],
  ['Shear', 'Shear', (t) => t.shear, (t, v) => ({ shear: v })],
  ['Rotate (degrees)', 'Rotate (degrees)', (t) => t.rotate?.degrees, (t, v) => ({ rotate: { ...t.rotate, degrees: v } })],
  ['Twist (degrees/unit)', 'Twist (degrees/unit)', (t) => t.twist?.degreesPerUnit, (t, v) => ({ twist: { ...t.twist, degreesPerUnit: v } })],
];

const isThicken = (transform) => describeEdit({ transform }) === 'Thicken';

// The methods an op can switch between: the ones that take any transform on
// a region (ARAP with handles moves a dragged part instead).
const SWITCHABLE = ['anarap', 'andefgrad', 'linear'];


/**
 * The selected op's fields. change(patch) sends {transform}, {method},
 * {direction} or {move} to setParameter; preview(patch) shows it live (a
 * number being typed); dropPreview() takes that back; redraw() shows the
 * op's values again.
 */
export function opFields(entry, { change, preview, dropPreview, redraw }) {
  const op = entry.op;
  const transform = op.transform ?? {};
  // write(value, send) builds the patch for `value` and hands it to send:
  // while typing a live preview of each number, on Enter or leaving the field
  // the change. A field left with a preview on screen and no change (the
  // op's own value typed again, or none) sends the value kept, so that the
  // screen shows the op's committed shape again (a value the op has makes no
  // step of the history).
  const number = (label, value, testId, write, name = undefined) => {
    let previewed = false;
    const settle = (typed) => {
      const wasPreviewed = previewed;
      previewed = false;
      if (Number.isFinite(typed)) write(typed, change);
      else if (wasPreviewed) write(value, change);
    };
    return h('label', { className: 'field op-amount' }, label,
      decimalInput({
        value: String(value),
        'data-testid': testId,
        ...(name ? { 'aria-label': name } : {}),
        // Esc takes the typed value back: the field shows the op's, and a preview of it is dropped.
        onkeydown: (event) => {
          if (event.key !== 'Escape') return;
          event.target.value = String(value);
          if (!previewed) return; // nothing shown: Esc goes on to the modeller (a solve's cancel)
          // Handled here: the modeller's Esc would take the drop's own restore for a solve to cancel.
          event.stopPropagation();
          dropPreview();
          previewed = false;
        },
        oninput: (event) => {
          const typed = parseDecimal(event.target.value);
          if (!Number.isFinite(typed)) return;
          previewed = true;
          write(typed, preview);
        },
        onchange: (event) => {
          const typed = parseDecimal(event.target.value);
          settle(typed);
          if (!Number.isFinite(typed)) redraw();
        },
        onblur: () => previewed && settle(value),
      }));
  };

  const amounts = AMOUNTS.filter(([, , read]) => typeof read(transform) === 'number').map(([key, label, read, write]) =>
    number(label, read(transform), `op-amount-${entry.id}-${key}`, (value, send) => send({ transform: write(transform, value) })));

  // An op written without a method has the core's default, AnARAP.
  const methodName = op.method ?? 'anarap';
  const method = SWITCHABLE.includes(methodName)
    ? h('label', { className: 'field op-amount' }, 'Method',
      h('select', {
        'data-testid': `op-method-${entry.id}`,
        onchange: (event) => change({ method: event.target.value }),
      }, SWITCHABLE.map((name) => h('option', { value: name, selected: name === methodName }, METHOD_NAMES[name]))))
    : null;

  // x, y, z fields of a vector: a value typed in one goes with the values in
  // the other two, so that a direction can go from x to z in any order of
  // typing. With `nonZero` (a direction), (0, 0, 0) is not sent: the fields
  // keep what is typed and say that one must be non-zero (it used to be
  // refused, and the field typed put back).
  const xyz = (label, vector, testId, write, { nonZero = false } = {}) => {
    const hint = h('p', { className: 'hint op-vector-hint', 'data-testid': `${testId}-hint`, 'aria-live': 'polite' });
    const fields = [0, 1, 2].map((axis) => number('xyz'[axis], Number(vector[axis].toFixed(4)), `${testId}-${'xyz'[axis]}`,
      (value, send) => {
        const typed = inputs.map((input, k) => (k === axis ? value : parseDecimal(input.value)));
        const next = typed.map((v, k) => (Number.isFinite(v) ? v : vector[k]));
        const zero = nonZero && next.every((v) => v === 0);
        hint.textContent = zero ? `A ${label.toLowerCase()} needs a component that is not 0: type one in another field.` : '';
        inputs.forEach((input) => input.toggleAttribute('aria-invalid', zero));
        if (zero) dropPreview(); // a value typed before, previewed, is not the fields' now
        else write(next, send);
      }, `${label} ${'xyz'[axis]}`));
    const inputs = fields.map((field) => field.querySelector('input'));
    return h('div', { className: 'op-direction' }, h('span', {}, label), h('div', { className: 'xyz' }, fields), hint);
  };

  // ARAP with handles moves the dragged part by `move`; the direction plays no part.
  if (op.method === 'arap') {
    return [...amounts, op.move ? xyz('Move', op.move, `op-move-${entry.id}`, (move, send) => send({ move })) : null];
  }
  return [...amounts, method, transformUsesDirection(transform) ? directionFields(entry, xyz, change) : null];
}

// A global direction as x, y, z; a curvature direction as its min/max
// choice; arrows and dense fields are shown, not edited here.
function directionFields(entry, xyz, change) {
  const direction = entry.op.direction;
  if (direction?.type === 'global') {
    return xyz('Direction', direction.vector, `op-direction-${entry.id}`,
      (vector, send) => send({ direction: { type: 'global', vector } }), { nonZero: true });
  }
  if (direction?.type === 'curvature') {
    return h('label', { className: 'field op-amount' }, 'Direction',
      h('select', {
        'data-testid': `op-direction-${entry.id}-curvature`,
        onchange: (event) => change({ direction: { ...direction, which: event.target.value } }),
      }, [['min', 'Min curvature'], ['max', 'Max curvature']].map(([value, text]) =>
        h('option', { value, selected: value === direction.which }, text))));
  }
  // Not given: the core's default (op.h), the loaded mesh's longest axis.
  const described = direction === undefined ? "the mesh's longest axis (none given)"
    : direction.type === 'constraints'
      ? `${direction.constraints.length} arrow${direction.constraints.length === 1 ? '' : 's'}, propagated`
      : 'a direction per vertex';
  return h('p', { className: 'op-direction-note' }, `Direction: ${described}`);
}

/**
 * The soft border of the op's region (the falloff of its select steps, in
 * model units along the surface): a new width gives the op a region of the
 * same steps with that falloff, through setRegion(steps).
 */
export function falloffField(entry, steps, { setRegion, redraw }) {
  // A brushed or edited selection is stored as its weights, soft edge and
  // all; a width adds a border beyond them ("Soft border 0" read as "hard").
  const weighted = steps.some((step) => step.region?.vertices);
  return h('label', { className: 'field op-amount', title: weighted
    ? 'The region is stored as its weights, with their own soft edge; this width adds a soft border beyond them, in model units along the surface'
    : "The width of the soft border around the edit's region, in model units along the surface" },
    weighted ? 'Extra soft border (units)' : 'Soft border (units)',
    decimalInput({
      value: String(steps[0]?.falloff ?? 0),
      'data-testid': `op-falloff-${entry.id}`,
      onchange: (event) => {
        const width = parseDecimal(event.target.value);
        if (Number.isFinite(width)) setRegion(steps.map((step) => ({ ...step, falloff: width })));
        else redraw();
      },
    }));
}
