// The public API's refusal of a bad argument: an Error whose `code` is the
// core's 'bad-parameter' (wasm/CONTRACT.md), so callers tell it from a failure.
export function badParameter(message) {
  return Object.assign(new Error(message), { code: 'bad-parameter' });
}

// What a solve stopped by cancel() rejects with: no failure, so no 'error'
// event (the reporter shows a notice), the same words as the worker's.
export const CANCELLED_MESSAGE = 'Cancelled: the solve was stopped; the mesh and its history are as they were.';

export function cancelledError() {
  return Object.assign(new Error(CANCELLED_MESSAGE), { code: 'cancelled' });
}

// What is refused while a drag on the view edits the mesh (editor.refuseDuringGesture).
export function gestureInProgressError() {
  return badParameter('an interactive edit is in progress: finish the drag first');
}

// What a load another one replaced rejects with (the last mesh asked for is
// the one shown): no failure either.
export function supersededLoadError() {
  return Object.assign(new Error('A later load replaced this one.'), { code: 'cancelled' });
}

// What an edit asked for on a mesh that a load replaced before the edit ran
// rejects with: not applied, and no failure (it was refused as "saved edits
// replay only on the mesh they were made on").
export function editOfReplacedMeshError() {
  return Object.assign(new Error('A new mesh was loaded before this edit ran: it was not applied.'), { code: 'cancelled' });
}
