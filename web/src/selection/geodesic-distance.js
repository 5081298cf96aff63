// Shortest edge-path distance from the vertices with weight > 0 (Dijkstra),
// bounded: vertices farther than `limit` keep Infinity, so a small falloff on
// a 200k-vertex mesh only walks the vertices near the selection.
export function geodesicDistances(adjacency, positions, seedWeights, limit) {
  const vertexCount = seedWeights.length;
  const distance = new Float64Array(vertexCount).fill(Infinity);
  const heap = new MinHeap();
  for (let i = 0; i < vertexCount; i++) {
    if (seedWeights[i] > 0) {
      distance[i] = 0;
      heap.push(0, i);
    }
  }
  const { offsets, neighbours } = adjacency;
  while (heap.size > 0) {
    const [d, i] = heap.pop();
    if (d > distance[i] || d > limit) continue;
    for (let k = offsets[i]; k < offsets[i + 1]; k++) {
      const j = neighbours[k];
      const dx = positions[3 * j] - positions[3 * i];
      const dy = positions[3 * j + 1] - positions[3 * i + 1];
      const dz = positions[3 * j + 2] - positions[3 * i + 2];
      const candidate = d + Math.sqrt(dx * dx + dy * dy + dz * dz);
      if (candidate < distance[j]) {
        distance[j] = candidate;
        heap.push(candidate, j);
      }
    }
  }
  return distance;
}

// Binary heap of (key, value) pairs in two parallel arrays.
class MinHeap {
  keys = [];
  values = [];

  get size() {
    return this.keys.length;
  }

  push(key, value) {
    const { keys, values } = this;
    let i = keys.length;
    keys.push(key);
    values.push(value);
    while (i > 0) {
      const parent = (i - 1) >> 1;
      if (keys[parent] <= key) break;
      keys[i] = keys[parent];
      values[i] = values[parent];
      i = parent;
    }
    keys[i] = key;
    values[i] = value;
  }

  pop() {
    const { keys, values } = this;
    const top = [keys[0], values[0]];
    const lastKey = keys.pop();
    const lastValue = values.pop();
    if (keys.length > 0) {
      let i = 0;
      const n = keys.length;
      for (;;) {
        let child = 2 * i + 1;
        if (child >= n) break;
        if (child + 1 < n && keys[child + 1] < keys[child]) child++;
        if (keys[child] >= lastKey) break;
        keys[i] = keys[child];
        values[i] = values[child];
        i = child;
      }
      keys[i] = lastKey;
      values[i] = lastValue;
    }
    return top;
  }
}
