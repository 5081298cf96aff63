// Selection weights of a region, as the core's selection.h defines them:
// weight 1 inside the region (or the weights a vertex list brings), then an
// optional soft border measured along mesh edges: w = max(w, smoothstep(1 - d/falloff)).
//
// Why a JavaScript copy of the core's rule: the public API's select() is
// synchronous and the brush must repaint on every pointer move, so the page
// keeps the weights itself and sends them to the solver before each edit.
import { geodesicDistances } from './geodesic-distance.js';

export class SelectionError extends Error {
  constructor(message) {
    super(message);
    this.name = 'SelectionError';
    this.code = 'bad-parameter';
  }
}

/** Weight per vertex (Float32Array) of `region` before falloff. */
export function regionWeights(positions, region) {
  const vertexCount = positions.length / 3;
  const weights = new Float32Array(vertexCount);
  if (!region || typeof region !== 'object') {
    throw new SelectionError('select() needs a region: {all: true}, {sphere}, {box} or {vertices}');
  }
  if (region.all) {
    weights.fill(1);
  } else if (region.sphere) {
    const { center, radius } = region.sphere;
    requireVector('sphere.center', center);
    if (!(Number.isFinite(radius) && radius >= 0)) {
      throw new SelectionError(`sphere.radius must be a number ≥ 0, got ${radius}`);
    }
    const radiusSquared = radius * radius;
    for (let i = 0; i < vertexCount; i++) {
      const dx = positions[3 * i] - center[0];
      const dy = positions[3 * i + 1] - center[1];
      const dz = positions[3 * i + 2] - center[2];
      if (dx * dx + dy * dy + dz * dz <= radiusSquared) weights[i] = 1;
    }
  } else if (region.box) {
    const { min, max } = region.box;
    requireVector('box.min', min);
    requireVector('box.max', max);
    for (let k = 0; k < 3; k++) {
      if (min[k] > max[k]) throw new SelectionError(`box.min[${k}] = ${min[k]} exceeds box.max[${k}] = ${max[k]}`);
    }
    for (let i = 0; i < vertexCount; i++) {
      let inside = true;
      for (let k = 0; k < 3 && inside; k++) {
        const value = positions[3 * i + k];
        inside = value >= min[k] && value <= max[k];
      }
      if (inside) weights[i] = 1;
    }
  } else if (region.vertices) {
    const { vertices, weights: given } = region;
    if (given && given.length !== vertices.length) {
      throw new SelectionError(`region has ${vertices.length} vertices but ${given.length} weights`);
    }
    for (let k = 0; k < vertices.length; k++) {
      const vertex = vertices[k];
      if (!Number.isInteger(vertex) || vertex < 0 || vertex >= vertexCount) {
        throw new SelectionError(`vertex ${vertex} does not exist: the mesh has ${vertexCount} vertices`);
      }
      const weight = given ? given[k] : 1;
      if (!(weight >= 0 && weight <= 1)) {
        throw new SelectionError(`weight ${weight} of vertex ${vertex} is outside [0, 1]`);
      }
      weights[vertex] = weight;
    }
  } else {
    throw new SelectionError('unknown region: use {all: true}, {sphere}, {box} or {vertices}');
  }
  return weights;
}

/** Adds a soft border of width `falloff` (model units) around the weights, in place. */
export function applyFalloff(weights, adjacency, positions, falloff) {
  if (!(Number.isFinite(falloff) && falloff >= 0)) {
    throw new SelectionError(`falloff must be a number ≥ 0, got ${falloff}`);
  }
  if (falloff === 0) return weights;
  const distance = geodesicDistances(adjacency, positions, weights, falloff);
  for (let i = 0; i < weights.length; i++) {
    const d = distance[i];
    if (d < falloff) weights[i] = Math.max(weights[i], smoothstep(1 - d / falloff));
  }
  return weights;
}

/** Combines new weights into the current ones: replace, add (max) or subtract. */
export function combineWeights(current, incoming, mode = 'replace') {
  if (mode === 'replace') return incoming;
  const result = new Float32Array(current.length);
  if (mode === 'add') {
    for (let i = 0; i < result.length; i++) result[i] = Math.max(current[i], incoming[i]);
  } else if (mode === 'subtract') {
    for (let i = 0; i < result.length; i++) result[i] = Math.min(current[i], 1 - incoming[i]);
  } else {
    throw new SelectionError(`mode must be 'replace', 'add' or 'subtract', got '${mode}'`);
  }
  return result;
}

export function countSelected(weights) {
  let count = 0;
  for (let i = 0; i < weights.length; i++) if (weights[i] > 0) count++;
  return count;
}

export function smoothstep(x) {
  const t = Math.min(Math.max(x, 0), 1);
  return t * t * (3 - 2 * t);
}

function requireVector(name, value) {
  if (!Array.isArray(value) && !ArrayBuffer.isView(value)) {
    throw new SelectionError(`${name} must be [x, y, z]`);
  }
  if (value.length !== 3 || ![...value].every(Number.isFinite)) {
    throw new SelectionError(`${name} must be three finite numbers, got [${[...value].join(', ')}]`);
  }
}
