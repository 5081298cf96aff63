// The public API's refusal of a bad argument: an Error whose `code` is the
// core's 'bad-parameter' (wasm/CONTRACT.md), so callers tell it from a failure.
export function badParameter(message) {
  return Object.assign(new Error(message), { code: 'bad-parameter' });
}
