// Area-weighted vertex normals (each vertex gets the sum of its triangles'
// cross products, normalised): what three's BufferGeometry.computeVertexNormals
// computes, over the typed arrays directly. A live preview shows a new shape
// every frame, and three's version, which reads and writes each corner
// through Vector3 objects, cost several milliseconds of each at 20k vertices.

/**
 * @param {Float32Array} positions  3 per vertex
 * @param {Uint32Array} triangles   3 vertex indices per triangle
 * @param {Float32Array} normals    3 per vertex, written
 */
export function writeVertexNormals(positions, triangles, normals) {
  normals.fill(0);
  for (let t = 0; t < triangles.length; t += 3) {
    const a = 3 * triangles[t], b = 3 * triangles[t + 1], c = 3 * triangles[t + 2];
    const abx = positions[b] - positions[a], aby = positions[b + 1] - positions[a + 1], abz = positions[b + 2] - positions[a + 2];
    const acx = positions[c] - positions[a], acy = positions[c + 1] - positions[a + 1], acz = positions[c + 2] - positions[a + 2];
    const nx = aby * acz - abz * acy, ny = abz * acx - abx * acz, nz = abx * acy - aby * acx;
    normals[a] += nx; normals[a + 1] += ny; normals[a + 2] += nz;
    normals[b] += nx; normals[b + 1] += ny; normals[b + 2] += nz;
    normals[c] += nx; normals[c + 1] += ny; normals[c + 2] += nz;
  }
  for (let i = 0; i < normals.length; i += 3) {
    // Not Math.hypot: V8's is several times slower, and it is per vertex per frame.
    const length = Math.sqrt(normals[i] * normals[i] + normals[i + 1] * normals[i + 1] + normals[i + 2] * normals[i + 2]);
    if (length > 0) {
      normals[i] /= length; normals[i + 1] /= length; normals[i + 2] /= length;
    }
  }
}
