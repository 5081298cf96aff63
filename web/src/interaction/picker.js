// Picking on the mesh with a three-mesh-bvh bounding volume hierarchy: the
// first surface hit under a canvas pixel, and the vertices inside a sphere
// (the brush). The BVH is built once per mesh, in the solver worker
// (worker/mesh-display.js: 'indirect', so the triangle order of the
// geometry, and so of exports, stays as loaded), and refitted lazily: edits
// only mark it stale, the next pick refits it.
import { DoubleSide, Raycaster, Sphere, Vector2, Vector3 } from 'three';
import { INTERSECTED, MeshBVH, NOT_INTERSECTED } from 'three-mesh-bvh';

const raycaster = new Raycaster();
const ndc = new Vector2();
const corner = new Vector3();
const sphere = new Sphere();

export class Picker {
  bvh = null;
  #stale = false;

  constructor(viewer, meshView) {
    this.viewer = viewer;
    this.meshView = meshView;
  }

  /** The mesh view's new geometry, with the worker's BVH of it (MeshPayload.bvh, serialized). */
  attach(serializedBvh) {
    this.bvh = MeshBVH.deserialize(serializedBvh, this.meshView.geometry, { setIndex: false });
    this.#stale = false;
  }

  markStale() {
    this.#stale = true;
  }

  #fresh() {
    if (this.#stale && this.bvh) {
      this.bvh.refit();
      this.#stale = false;
    }
    return this.bvh;
  }

  /**
   * First hit under canvas pixel (x, y), or null.
   * @returns {{point: number[], normal: number[], triangle: number, vertex: number}|null}
   */
  pick(x, y) {
    const bvh = this.#fresh();
    if (!bvh) return null;
    const { x: nx, y: ny } = this.viewer.toNdc(x, y);
    raycaster.setFromCamera(ndc.set(nx, ny), this.viewer.camera);
    const hit = bvh.raycastFirst(raycaster.ray, DoubleSide);
    if (!hit) return null;
    const index = this.meshView.geometry.index.array;
    const positions = this.meshView.geometry.getAttribute('position');
    let vertex = -1;
    let best = Infinity;
    for (let k = 0; k < 3; k++) {
      const candidate = index[3 * hit.faceIndex + k];
      const distance = corner.fromBufferAttribute(positions, candidate).distanceToSquared(hit.point);
      if (distance < best) {
        best = distance;
        vertex = candidate;
      }
    }
    // Face normal towards the viewer, so open meshes seen from behind work too.
    const normal = hit.face.normal.clone();
    if (normal.dot(raycaster.ray.direction) > 0) normal.negate();
    return { point: hit.point.toArray(), normal: normal.toArray(), triangle: hit.faceIndex, vertex };
  }

  /** Calls visit(vertex, distance) once for every vertex within `radius` of `center`. */
  forEachVertexInSphere(center, radius, visit) {
    const bvh = this.#fresh();
    if (!bvh) return;
    sphere.center.fromArray(center);
    sphere.radius = radius;
    const index = this.meshView.geometry.index.array;
    const positions = this.meshView.geometry.getAttribute('position');
    const seen = new Set();
    bvh.shapecast({
      intersectsBounds: (box) => {
        return sphere.intersectsBox(box) ? INTERSECTED : NOT_INTERSECTED;
      },
      intersectsTriangle: (triangle, triangleIndex) => {
        for (let k = 0; k < 3; k++) {
          const vertex = index[3 * triangleIndex + k];
          if (seen.has(vertex)) continue;
          seen.add(vertex);
          const distance = corner.fromBufferAttribute(positions, vertex).distanceTo(sphere.center);
          if (distance <= radius) visit(vertex, distance);
        }
        return false;
      },
    });
  }
}

