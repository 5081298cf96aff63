// What the page needs to draw and pick a new mesh, computed in the solver
// worker: the vertex normals and the picking BVH (interaction/picker.js).
// On the page's main thread they took one task of 0.9 s for the 200k koala
// and 2 s for an 800k-vertex scan (the BVH 1.3 s, three's normals 0.5 s),
// a frozen tab right when the mesh appears.
//
// The BVH is built with three-mesh-bvh's defaults, indirect, over the very
// arrays the page draws: the float32 positions and the triangles of the
// MeshPayload. Indirect mode leaves the index as it is (its own buffer holds
// the triangle order), so the page attaches the tree to its copy of those
// arrays (MeshBVH.deserialize) and every pick is the one a BVH built on the
// page would give.
import { BufferAttribute, BufferGeometry } from 'three';
import { MeshBVH } from 'three-mesh-bvh';
import { writeVertexNormals } from '../viewer/vertex-normals.js';

/**
 * @param {Float32Array} positions  3 per vertex (the page's copy is drawn)
 * @param {Uint32Array} triangles   3 vertex indices per triangle
 * @returns {{normals: Float32Array, bvh: object, transfer: ArrayBuffer[]}}
 *   bvh: MeshBVH.serialize's data without the index (the page has the triangles)
 */
export function meshDisplay(positions, triangles) {
  const normals = new Float32Array(positions.length);
  writeVertexNormals(positions, triangles, normals);
  const geometry = new BufferGeometry();
  geometry.setAttribute('position', new BufferAttribute(positions, 3));
  geometry.setIndex(new BufferAttribute(triangles, 1));
  const tree = new MeshBVH(geometry, { indirect: true });
  const { version, roots, indirectBuffer } = MeshBVH.serialize(tree, { cloneBuffers: false });
  return { normals, bvh: { version, roots, indirectBuffer }, transfer: [normals.buffer, ...roots, indirectBuffer.buffer] };
}
