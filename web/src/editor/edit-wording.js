// What the editor says about edits and failures, in plain words: the undo
// label of an edit, the fold-over warning, and the one way an error reaches
// the user (reporter()).

const TRANSFORM_NAMES = { scale: 'Stretch', thickness: 'Thicken', shear: 'Shear', rotate: 'Rotate', twist: 'Twist' };
export const METHOD_NAMES = { anarap: 'AnARAP', andefgrad: 'AnDefGrad', arap: 'ARAP', linear: 'Linear' };

export function describeEdit(op) {
  if (typeof op !== 'object' || op === null) return 'The edit';
  if (op.method === 'arap' && op.move) return 'Move (ARAP)';
  const kind = Object.keys(op.transform ?? {}).find((key) => key in TRANSFORM_NAMES) ?? 'scale';
  // The Thicken tool's op is a scale across the direction only: [1, sv].
  const scale = op.transform?.scale;
  const across = kind === 'scale' && Array.isArray(scale) && scale.length === 2 && scale[0] === 1 && scale[1] !== 1;
  const name = across ? 'Thicken' : TRANSFORM_NAMES[kind];
  // An op not resolved yet may leave its method to the core's default: no method named then.
  return op.method ? `${name} (${METHOD_NAMES[op.method] ?? op.method})` : name;
}

export function foldOverWarning(count) {
  return `${count} triangle${count === 1 ? '' : 's'} folded over: reduce the amount or the falloff.`;
}

/**
 * Returns report(error, context): emits 'error' {code, message} (the banner
 * and the API's event) once per error, whoever catches it, and returns the
 * Error to throw on, with the code of the layer that raised it (core codes
 * pass through unchanged). `context` says what was refused ("Stretch was not
 * applied").
 */
export function reporter(emit) {
  const reported = new WeakSet();
  return (error, context) => {
    if (reported.has(error)) return error;
    const code = error?.code ?? 'internal';
    const detail = error?.message ?? String(error);
    // A cancel is the user's own doing, not a failure: a notice says so,
    // without the context's "failed".
    const message = context && code !== 'cancelled' ? `${context}: ${detail}` : detail;
    if (code === 'cancelled') emit('notice', { message, source: 'cancel' });
    else emit('error', { code, message });
    const wrapped = Object.assign(new Error(message), { code, cause: error });
    reported.add(wrapped);
    return wrapped;
  };
}

/**
 * A core refusal of a change made in the page (an amount, a soft border, an
 * op moved or turned on), in the page's words. The core names a document's
 * parts by their place ("document.ops[0] (id 'op-1').op.transform: scale su
 * must be positive"), which the page never shows; the Edits list shows the
 * op's label and its amounts' names ("Stretch (AnARAP): stretch along (su)
 * must be positive"). `labelled: false` leaves the op's label out (a
 * commit's refusal, whose context names the edit already). Anything else is
 * returned as it is.
 */
export function inPageWords(error, document, { labelled = true } = {}) {
  if (typeof error?.message !== 'string' || !document) return error;
  const labelOf = (entry, fallback) => (entry ? entry.label || entry.id : fallback);
  const message = error.message
    // "…(id 'a').op.transform has an unknown field" keeps "transform" (else "Stretch:  has …").
    .replace(/document\.ops\[\d+\] \(id '([^']*)'\)((?:\.op)?(?:\.transform)?)(\.|: )?/g, (_, id, path, separator) => {
      const label = labelled ? `${labelOf(document.ops.find((entry) => entry.id === id), id)}: ` : '';
      return separator || !path ? label : label + path.split('.').pop();
    })
    .replace(/document\.regions\[\d+\] \(name '([^']*)'\)(?:\.steps\[(\d+)\])?\.?/g, (_, name, step) => {
      const owner = document.ops.find((entry) => entry.region === name);
      const which = step && step !== '0' ? ` (step ${Number(step) + 1})` : '';
      return `${owner ? `the region of ${labelOf(owner)}` : 'the region'}${which}: `;
    })
    // An edit's own op, before it is in the document ("op.transform: ...").
    .replace(/^op\.transform(?::\s*|\.)/, '')
    .replace(/\bscale su\b/g, 'stretch along (su)')
    .replace(/\bscale sv\b/g, 'stretch across (sv)')
    .replace(/\bfalloff\b/g, 'soft border (falloff)');
  if (message === error.message) return error;
  return Object.assign(new Error(message), { code: error.code, cause: error });
}

/**
 * A core refusal of flatten options in the panel's words: "flatten:
 * options.compress[0] must be positive" says the call twice (after "Flatten
 * failed") and names no field the page shows: "stretch along (compress[0])
 * must be positive". The option's own name stays for api callers.
 */
export function flattenInPageWords(error) {
  if (typeof error?.message !== 'string' || !error.message.startsWith('flatten: options')) return error;
  const message = error.message
    .replace(/^flatten: options\.compress\[1\]/, 'stretch across (compress[1])')
    .replace(/^flatten: options\.compress(\[0\])?/, (_, index) => `stretch along (compress${index ?? ''})`)
    .replace(/^flatten: options\./, '');
  return Object.assign(new Error(message), { code: error.code, cause: error });
}
