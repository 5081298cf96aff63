// The page's copy of the mesh being edited: committed positions, triangles,
// the positions as loaded (for reset and the distortion heat map), selection
// weights and the mesh check's report.
//
// Arrays are treated as immutable: an edit replaces `positions` or `selection`
// with a new array instead of writing into it, so undo commands can keep
// references instead of copies.
import { buildVertexAdjacency } from '../selection/mesh-adjacency.js';

export class MeshDocument {
  #adjacency = null;
  #bounds = null;
  #boundsFor = null; // the positions #bounds are of

  /**
   * @param {{name: string, positions: Float32Array, triangles: Uint32Array, info: object,
   *   display: {normals: Float32Array, bvh: object}, gltf?: import('../io/gltf-source.js').GltfSource}} mesh
   *   display: the worker's vertex normals and picking BVH of the mesh as
   *   loaded (worker/mesh-display.js), for the view to draw and pick it; the
   *   view takes their arrays over (it writes them as the shape changes);
   *   gltf: the scene of a glTF file, which a GLB export writes the shape into
   */
  constructor({ name, positions, triangles, info, display, gltf = null }) {
    this.name = name;
    this.positions = positions;
    this.triangles = triangles;
    this.loadedPositions = positions;
    this.info = info;
    this.display = display;
    this.gltf = gltf;
    this.selection = new Float32Array(positions.length / 3);
    this.selectionCount = 0;
    // Bumped on every selection change, so the solver client knows when to resend.
    this.selectionVersion = 0;
  }

  get vertexCount() {
    return this.positions.length / 3;
  }

  get triangleCount() {
    return this.triangles.length / 3;
  }

  get adjacency() {
    this.#adjacency ??= buildVertexAdjacency(this.vertexCount, this.triangles);
    return this.#adjacency;
  }

  /** `count`: the vertices with weight > 0, when the core has counted them already. */
  setSelection(weights, count = countSelected(weights)) {
    this.selection = weights;
    this.selectionCount = count;
    this.selectionVersion++;
  }

  /**
   * The side an open surface faces (a garment patch, a face scan): the unit
   * sum of its triangles' area normals, or null for a closed mesh or one
   * that faces no one side (under 30 % of its area). The view first looks
   * at that side: from behind, arrows and glyphs drawn on it were hidden.
   */
  facing() {
    if (this.info.boundaryLoops === 0) return null;
    const p = this.positions;
    const t = this.triangles;
    let [sx, sy, sz, area] = [0, 0, 0, 0];
    for (let k = 0; k < t.length; k += 3) {
      const a = 3 * t[k], b = 3 * t[k + 1], c = 3 * t[k + 2];
      const [ux, uy, uz] = [p[b] - p[a], p[b + 1] - p[a + 1], p[b + 2] - p[a + 2]];
      const [vx, vy, vz] = [p[c] - p[a], p[c + 1] - p[a + 1], p[c + 2] - p[a + 2]];
      const [nx, ny, nz] = [uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx];
      sx += nx;
      sy += ny;
      sz += nz;
      area += Math.hypot(nx, ny, nz);
    }
    const length = Math.hypot(sx, sy, sz);
    return length > 0.3 * area && length > 0 ? [sx / length, sy / length, sz / length] : null;
  }

  /**
   * Axis-aligned bounds of the committed positions: {min, max, center,
   * diagonal}, frozen. Kept until `positions` is replaced: a drag asks at
   * every pointer move (0.5 ms at 50k vertices).
   */
  bounds() {
    if (this.#boundsFor !== this.positions) {
      this.#bounds = deepFreeze(boundsOf(this.positions));
      this.#boundsFor = this.positions;
    }
    return this.#bounds;
  }
}

function deepFreeze(bounds) {
  for (const value of Object.values(bounds)) if (typeof value === 'object') Object.freeze(value);
  return Object.freeze(bounds);
}

// The core's meaning of "selected" (Session.select's count): weight > 0.
function countSelected(weights) {
  let count = 0;
  for (let i = 0; i < weights.length; i++) if (weights[i] > 0) count++;
  return count;
}

export function boundsOf(positions) {
  const min = [Infinity, Infinity, Infinity];
  const max = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < positions.length; i += 3) {
    for (let k = 0; k < 3; k++) {
      const value = positions[i + k];
      if (value < min[k]) min[k] = value;
      if (value > max[k]) max[k] = value;
    }
  }
  const center = [0, 1, 2].map((k) => (min[k] + max[k]) / 2);
  const diagonal = Math.hypot(max[0] - min[0], max[1] - min[1], max[2] - min[2]);
  return { min, max, center, diagonal };
}
