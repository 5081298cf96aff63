// Growing and shrinking a weighted selection by one ring of vertices
// (dilation and erosion of the weights over the one-ring), and inverting it.
// Page-side edits of the weights, like a brush stroke: the core has no such
// rule (its selection is regions and a geodesic falloff, Session.select), so
// nothing here repeats it; the result reaches the core through setSelection,
// which checks it.
export function growSelection(weights, adjacency) {
  const { offsets, neighbours } = adjacency;
  const grown = new Float32Array(weights);
  for (let i = 0; i < weights.length; i++) {
    for (let k = offsets[i]; k < offsets[i + 1]; k++) {
      const w = weights[neighbours[k]];
      if (w > grown[i]) grown[i] = w;
    }
  }
  return grown;
}

export function shrinkSelection(weights, adjacency) {
  const { offsets, neighbours } = adjacency;
  const shrunk = new Float32Array(weights);
  for (let i = 0; i < weights.length; i++) {
    for (let k = offsets[i]; k < offsets[i + 1]; k++) {
      const w = weights[neighbours[k]];
      if (w < shrunk[i]) shrunk[i] = w;
    }
  }
  return shrunk;
}

export function invertSelection(weights) {
  const inverted = new Float32Array(weights.length);
  for (let i = 0; i < weights.length; i++) inverted[i] = 1 - weights[i];
  return inverted;
}
