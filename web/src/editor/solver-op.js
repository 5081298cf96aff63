// Checks a public-API edit (issue 3's `op`) and completes it into the
// session's request (wasm/CONTRACT.md): screen drags get the camera and the
// picked anchor point; ARAP with handles gets its handles and pins from the
// selection.
const METHODS = ['anarap', 'andefgrad', 'arap', 'linear'];
const DIRECTION_TYPES = ['global', 'curvature', 'screen', 'constraints'];

function badParameter(message) {
  return Object.assign(new Error(message), { code: 'bad-parameter' });
}

export function validateOp(op) {
  if (!op || typeof op !== 'object') throw badParameter('deform() needs an op: {method, direction, transform}');
  if (!METHODS.includes(op.method)) {
    throw badParameter(`method must be one of ${METHODS.join(', ')}, got '${op.method}'`);
  }
  if (op.method !== 'arap') {
    if (!op.direction || !DIRECTION_TYPES.includes(op.direction.type)) {
      throw badParameter(`direction.type must be one of ${DIRECTION_TYPES.join(', ')}, got '${op.direction?.type}'`);
    }
    if (!op.transform || typeof op.transform !== 'object') {
      throw badParameter('transform is missing: give scale, shear, rotate or twist');
    }
  }
  if (op.direction?.type === 'screen') {
    for (const key of ['from', 'to']) {
      const point = op.direction[key];
      if (!Array.isArray(point) || point.length !== 2 || !point.every(Number.isFinite)) {
        throw badParameter(`direction.${key} must be [x, y] in canvas pixels`);
      }
    }
  }
}

/**
 * @param {object} op                   the public op
 * @param {import('./mesh-document.js').MeshDocument} document
 * @param {{cameraState(): object, pick(x: number, y: number): object|null}|null} view
 */
export function toSolverOp(op, document, view) {
  const solverOp = { ...op };
  if (op.direction) solverOp.direction = { ...op.direction };
  if (op.direction?.type === 'screen' && !op.direction.camera) {
    if (!view) throw badParameter('a screen direction needs the viewer');
    const anchor = op.direction.anchor ?? view.pick(op.direction.from[0], op.direction.from[1])?.point ?? selectionCentre(document);
    delete solverOp.direction.anchor; // the session takes it inside the camera
    solverOp.direction.camera = { ...view.cameraState(), anchor };
  }
  if (op.method === 'arap') {
    solverOp.direction ??= { type: 'global', vector: [1, 0, 0] };
    solverOp.transform ??= {};
    solverOp.move ??= [0, 0, 0];
    if (!op.handles) Object.assign(solverOp, arapHandlesAndPins(document));
  }
  return solverOp;
}

// ARAP with handles in the modelling sense (Sorkine & Alexa): the fully
// selected vertices are the handle and move with the drag, the soft border
// (0 < weight < 1) deforms as rigidly as possible, the unselected rest is
// pinned. With nothing selected the whole mesh is the handle.
function arapHandlesAndPins(document) {
  const { selection, selectionCount, vertexCount } = document;
  if (selectionCount === 0) return { handles: Array.from({ length: vertexCount }, (_, i) => i), pins: [] };
  const handles = [];
  const pins = [];
  for (let i = 0; i < vertexCount; i++) {
    if (selection[i] >= 0.999) handles.push(i);
    else if (selection[i] === 0) pins.push(i);
  }
  return { handles, pins };
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
