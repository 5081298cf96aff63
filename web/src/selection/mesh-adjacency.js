// Vertex adjacency of a triangle mesh in compressed rows (CSR): the one-ring
// neighbours of vertex i are neighbours[offsets[i] .. offsets[i+1]). Built once
// per loaded mesh, on the first grow or shrink (selection-morphology.js).
export function buildVertexAdjacency(vertexCount, triangles) {
  const degree = new Uint32Array(vertexCount + 1);
  for (let t = 0; t < triangles.length; t += 3) {
    for (let k = 0; k < 3; k++) {
      degree[triangles[t + k]] += 2; // each corner meets two edges of its triangle
    }
  }
  const rawOffsets = new Uint32Array(vertexCount + 1);
  for (let i = 0; i < vertexCount; i++) rawOffsets[i + 1] = rawOffsets[i] + degree[i];
  const raw = new Uint32Array(rawOffsets[vertexCount]);
  const fill = rawOffsets.slice(0, vertexCount);
  for (let t = 0; t < triangles.length; t += 3) {
    const a = triangles[t], b = triangles[t + 1], c = triangles[t + 2];
    raw[fill[a]++] = b; raw[fill[a]++] = c;
    raw[fill[b]++] = c; raw[fill[b]++] = a;
    raw[fill[c]++] = a; raw[fill[c]++] = b;
  }
  // Every interior edge appears twice per vertex (once per adjacent triangle): dedupe.
  const offsets = new Uint32Array(vertexCount + 1);
  const neighbours = new Uint32Array(raw.length);
  let count = 0;
  for (let i = 0; i < vertexCount; i++) {
    offsets[i] = count;
    const row = raw.subarray(rawOffsets[i], rawOffsets[i + 1]).sort();
    for (let k = 0; k < row.length; k++) {
      if (k === 0 || row[k] !== row[k - 1]) neighbours[count++] = row[k];
    }
  }
  offsets[vertexCount] = count;
  return { offsets, neighbours: neighbours.slice(0, count) };
}
