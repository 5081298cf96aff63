// Form fields bound to a settings section: numbers, selects, checkboxes and
// xyz vectors. A field shows the setting's current value (a drag writes its
// amount there live) unless the user is typing in it; a typed value is
// replaced at once by the value kept (a number field's min/max clamp it), so
// the field never shows a number that is not the one used.
//
// A value not taken (not a number, out of the field's bounds) is said in a
// notice (settings 'refused'); a value the same field then takes as typed
// says that notice is moot (settings 'accepted'): "'1,000.5' is not a
// number; 1 is kept" stood beside the 2 typed next.
// A number field's min/max are the panel's own bounds (a brush radius in
// percent); an `integer` field (the iteration cap) refuses a fraction: "2.5"
// was kept, and every later edit failed in the core ("op.maxIterations must
// be an integer"). `step` is only the keys' increment, no rule. Amounts the core validates (limits.h: stretch, shear, angles,
// the twist rate) get none here: the core refuses an out-of-range value with
// a message naming the field and its range, and the field keeps showing it.
import { h } from './dom.js';
import { decimalInput, parseDecimal } from './decimal-input.js';

export function numberField(settings, sectionName, { key, label, min, max, integer = false }) {
  const field = `${sectionName}-${key}`;
  const input = decimalInput({ id: field, inputMode: integer ? 'numeric' : 'decimal' });
  // The field's rule, for a value typed here and one put back after a reload (Settings.restore).
  settings.defineRule(sectionName, key, (value) => (Number.isFinite(value) && (!integer || Number.isInteger(value))
    ? clamp(value, min, max)
    : undefined));
  const sync = () => {
    if (document.activeElement !== input) input.value = settings.values[sectionName][key];
  };
  input.addEventListener('change', () => {
    const typed = input.value.trim();
    const value = parseDecimal(typed);
    const fraction = integer && Number.isFinite(value) && !Number.isInteger(value);
    const accepted = settings.accepted(sectionName, key, value);
    const taken = accepted !== undefined;
    if (taken) settings.update(sectionName, { [key]: accepted });
    const kept = settings.values[sectionName][key];
    input.value = kept;
    // Said, not only undone: "abc" used to put the old value back silently.
    if (fraction) refused(settings, field, `${label}: '${typed}' is not a whole number; ${kept} is kept`);
    else if (!taken && typed !== '') refused(settings, field, `${label}: '${typed}' is not a number; ${kept} is kept`);
    else if (taken && value !== kept) refused(settings, field, `${label}: ${typed} is out of range (${rangeText(min, max)}); ${kept} is used`);
    else if (taken) settings.emit('accepted', { field });
  });
  settings.on('change', ({ section }) => section === sectionName && sync());
  // A value set while the user was in the field (a new mesh's twist rate) shows once they leave it.
  input.addEventListener('blur', sync);
  sync();
  return h('label', { className: 'field', for: input.id }, h('span', {}, label), input);
}

export function selectField(settings, sectionName, { key, label, options }) {
  const select = h(
    'select',
    { id: `${sectionName}-${key}` },
    options.map(([value, text]) => h('option', { value }, text)),
  );
  settings.defineRule(sectionName, key, (value) => (options.some(([option]) => option === value) ? value : undefined));
  const sync = () => (select.value = settings.values[sectionName][key]);
  select.addEventListener('change', () => settings.update(sectionName, { [key]: select.value }));
  settings.on('change', ({ section }) => section === sectionName && sync());
  sync();
  return h('label', { className: 'field', for: select.id }, h('span', {}, label), select);
}

export function checkboxField(settings, sectionName, { key, label }) {
  const input = h('input', { type: 'checkbox', id: `${sectionName}-${key}` });
  settings.defineRule(sectionName, key, (value) => (typeof value === 'boolean' ? value : undefined));
  const sync = () => (input.checked = settings.values[sectionName][key]);
  input.addEventListener('change', () => settings.update(sectionName, { [key]: input.checked }));
  settings.on('change', ({ section }) => section === sectionName && sync());
  sync();
  return h('label', { className: 'field field-checkbox', for: input.id }, input, h('span', {}, label));
}

/** xyz fields; a direction (the default) must be non-zero, a point (`point: true`) need not. */
export function vectorField(settings, sectionName, { key, label, point = false }) {
  const inputs = [0, 1, 2].map((axis) =>
    decimalInput({ 'aria-label': `${label} ${'xyz'[axis]}` }),
  );
  const isVector = (value) => Array.isArray(value) && value.length === 3 && value.every(Number.isFinite);
  settings.defineRule(sectionName, key, (value) => (isVector(value) && (point || Math.hypot(...value) > 0) ? [...value] : undefined));
  const sync = () => {
    const vector = settings.values[sectionName][key];
    inputs.forEach((input, axis) => document.activeElement !== input && (input.value = vector[axis]));
  };
  for (const input of inputs) {
    input.addEventListener('change', () => {
      const vector = inputs.map((field) => parseDecimal(field.value));
      const accepted = settings.accepted(sectionName, key, vector);
      if (accepted !== undefined) {
        settings.update(sectionName, { [key]: accepted });
        settings.emit('accepted', { field: `${sectionName}-${key}` });
      } else {
        const kept = settings.values[sectionName][key];
        refused(settings, `${sectionName}-${key}`, vector.every(Number.isFinite)
          ? `${label}: (0, 0, 0) is no direction; (${kept.join(', ')}) is kept`
          : `${label}: every component must be a number; (${kept.join(', ')}) is kept`);
      }
      const kept = settings.values[sectionName][key];
      inputs.forEach((field, axis) => (field.value = kept[axis]));
    });
  }
  settings.on('change', ({ section }) => section === sectionName && sync());
  sync();
  return h('div', { className: 'field field-vector' }, h('span', {}, label), h('div', { className: 'xyz' }, inputs));
}

/** Shows `element` only while predicate(settings section values) holds. */
export function showWhen(settings, sectionName, element, predicate) {
  const sync = () => (element.hidden = !predicate(settings.values[sectionName]));
  settings.on('change', ({ section }) => section === sectionName && sync());
  sync();
  return element;
}

// A value field `field` (its section-key) did not take, for the page to
// say (settings 'refused', shown as a notice by the full UI).
function refused(settings, field, message) {
  settings.emit('refused', { message, field });
}

function rangeText(min, max) {
  if (min !== undefined && max !== undefined) return `${min} to ${max}`;
  return min !== undefined ? `at least ${min}` : `at most ${max}`;
}

function clamp(value, min, max) {
  return Math.min(Math.max(value, min ?? -Infinity), max ?? Infinity);
}
