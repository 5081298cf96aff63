// Completes a public-API edit (issue 3's `op`) into the session's request
// (wasm/CONTRACT.md): screen drags get the camera and the picked anchor point.
// Everything else is the core's (core/include/anisoform/op.h): it checks the
// op, naming the field, and fills in the defaults that depend on the mesh
// (the direction, the twist origin, ARAP's handles and pins from the selection).
import { badParameter } from '../shared/errors.js';

/**
 * @param {object} op                   the public op
 * @param {import('./mesh-document.js').MeshDocument} document
 * @param {{cameraState(): object, pick(x: number, y: number): object|null}|null} view
 */
export function toSolverOp(op, document, view) {
  // Not an object: the core refuses it as it is ("op must be an object"); spread, a string would be an op of fields '0', '1', …
  if (typeof op !== 'object' || op === null || Array.isArray(op)) return op;
  const solverOp = { ...op };
  if (op.direction) solverOp.direction = { ...op.direction };
  if (op.direction?.type === 'screen' && !op.direction.camera) {
    if (!view) throw badParameter('a screen direction needs the viewer');
    // A malformed `from` is the core's to refuse, naming it; only a pair is picked at.
    const from = Array.isArray(op.direction.from) ? op.direction.from : null;
    const anchor = op.direction.anchor ?? (from && view.pick(from[0], from[1])?.point) ?? selectionCentre(document);
    delete solverOp.direction.anchor; // the session takes it inside the camera
    solverOp.direction.camera = { ...view.cameraState(), anchor };
  }
  return solverOp;
}

/** Weighted centre of the selection (the whole mesh when nothing is selected). */
export function selectionCentre(document) {
  const { positions, selection, selectionCount } = document;
  const centre = [0, 0, 0];
  let total = 0;
  for (let i = 0; i < positions.length / 3; i++) {
    const weight = selectionCount === 0 ? 1 : selection[i];
    if (weight <= 0) continue;
    centre[0] += weight * positions[3 * i];
    centre[1] += weight * positions[3 * i + 1];
    centre[2] += weight * positions[3 * i + 2];
    total += weight;
  }
  return centre.map((value) => value / total);
}
