// Per-vertex distortion against the mesh as loaded, for the heat map:
//   'area'    log2 of the area ratio of the vertex's triangles (now / loaded)
//   'stretch' log2 of the triangle's principal stretch that deviates most
//             from 1 (the singular values of the loaded-to-current map),
//             averaged over the vertex's triangles by loaded area
// Measured against the mesh as loaded, so the map shows all edits so far.
// Computed on the page rather than asked from the worker's distortion(): the
// map then follows every live-preview frame without a round trip (about
// 20 ms for 400k triangles).
export const DISTORTION_KINDS = ['area', 'stretch'];

export function computeDistortion(kind, loaded, current, triangles) {
  const vertexCount = loaded.length / 3;
  const sum = new Float64Array(vertexCount);
  const weight = new Float64Array(vertexCount);
  const currentArea = kind === 'area' ? new Float64Array(vertexCount) : null;
  for (let t = 0; t < triangles.length; t += 3) {
    const a = triangles[t], b = triangles[t + 1], c = triangles[t + 2];
    const e1 = edge(loaded, a, b), e2 = edge(loaded, a, c);
    const f1 = edge(current, a, b), f2 = edge(current, a, c);
    const g11 = dot(e1, e1), g12 = dot(e1, e2), g22 = dot(e2, e2);
    const restDeterminant = g11 * g22 - g12 * g12;
    if (!(restDeterminant > 0)) continue; // a zero-area triangle has no ratio
    const restArea = Math.sqrt(restDeterminant) / 2;
    if (kind === 'area') {
      const h11 = dot(f1, f1), h12 = dot(f1, f2), h22 = dot(f2, f2);
      const area = Math.sqrt(Math.max(h11 * h22 - h12 * h12, 0)) / 2;
      for (const v of [a, b, c]) {
        weight[v] += restArea;
        currentArea[v] += area;
      }
    } else {
      const value = dominantLog2Stretch(g11, g12, g22, dot(f1, f1), dot(f1, f2), dot(f2, f2));
      for (const v of [a, b, c]) {
        weight[v] += restArea;
        sum[v] += restArea * value;
      }
    }
  }
  const values = new Float32Array(vertexCount);
  for (let v = 0; v < vertexCount; v++) {
    if (weight[v] === 0) continue;
    values[v] = kind === 'area' ? Math.log2(Math.max(currentArea[v], 1e-30) / weight[v]) : sum[v] / weight[v];
  }
  return values;
}

// The squared singular values of the map are the eigenvalues of G⁻¹H, where
// G and H are the Gram matrices of the triangle's edges before and after.
function dominantLog2Stretch(g11, g12, g22, h11, h12, h22) {
  const determinantG = g11 * g22 - g12 * g12;
  // M = G⁻¹ H
  const m11 = (g22 * h11 - g12 * h12) / determinantG;
  const m12 = (g22 * h12 - g12 * h22) / determinantG;
  const m21 = (-g12 * h11 + g11 * h12) / determinantG;
  const m22 = (-g12 * h12 + g11 * h22) / determinantG;
  const trace = m11 + m22;
  const determinant = m11 * m22 - m12 * m21;
  const root = Math.sqrt(Math.max(trace * trace / 4 - determinant, 0));
  const large = Math.max(trace / 2 + root, 1e-30);
  const small = Math.max(trace / 2 - root, 1e-30);
  const logLarge = 0.5 * Math.log2(large);
  const logSmall = 0.5 * Math.log2(small);
  return Math.abs(logLarge) >= Math.abs(logSmall) ? logLarge : logSmall;
}

function edge(positions, from, to) {
  return [
    positions[3 * to] - positions[3 * from],
    positions[3 * to + 1] - positions[3 * from + 1],
    positions[3 * to + 2] - positions[3 * from + 2],
  ];
}

function dot(u, v) {
  return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
}
