// A loaded glTF scene kept beside the mesh the solver edits, so that a GLB
// export writes the edited shape into the file's own scene (its nodes and
// their transforms, materials, textures, UVs and vertex colours), and the
// view can draw the shape with the file's materials (viewer/gltf-display.js).
// The solver's mesh is every triangle primitive in world coordinates, merged
// and welded (import-gltf.js, Session.setMesh): `vertexMap`
// (Session.inputVertexMap) takes each primitive's vertices to the solver's.
import { BufferAttribute, Matrix3, Matrix4, Vector3 } from 'three';
import { GLTFExporter } from 'three/addons/exporters/GLTFExporter.js';

import { weldedNormals } from './welded-normals.js';

// Two copies of a welded vertex whose normals in the file agree this closely
// lie on a smooth surface split for its UVs or colours: they get the welded
// vertex's one normal. Copies that differ lie on a hard edge and keep a
// normal of their own side (as computeVertexNormals gives it).
const SAME_NORMAL_COS = 0.9999;

export class GltfSource {
  #smooth = null;

  /**
   * @param {import('three').Object3D} scene  GLTFLoader's scene, world matrices up to date
   * @param {{mesh: import('three').Mesh, offset: number}[]} parts  the merged primitives, in
   *   their order in the solver's input, each with its own geometry
   */
  constructor(scene, parts) {
    this.scene = scene;
    this.parts = parts;
    /** @type {Uint32Array | null} */
    this.vertexMap = null;
  }

  /** Session.inputVertexMap of the merged arrays: which solver vertex each one became. */
  attach(vertexMap, weldedCount) {
    this.vertexMap = vertexMap;
    this.#smooth = this.#smoothVertices(weldedCount);
  }

  /**
   * The scene with `positions` (the solver's, xyz per vertex, world
   * coordinates) written into its primitives, as GLB bytes.
   * @returns {Promise<ArrayBuffer>}
   */
  async exportGlb(positions, triangles) {
    this.writeShape(positions, triangles);
    return new GLTFExporter().parseAsync(this.scene, { binary: true });
  }

  /**
   * Writes `positions` (the solver's) into the scene's primitives, their
   * normals recomputed unless `normals` is false (a live preview frame: the
   * positions alone cost a fifth as much).
   */
  writeShape(positions, triangles, { normals = true } = {}) {
    const welded = normals ? weldedNormals(positions, triangles) : null;
    const world = new Vector3();
    const toLocal = new Matrix4();
    const normalToLocal = new Matrix3();
    for (const { mesh, offset } of this.parts) {
      const geometry = mesh.geometry;
      const position = floatAttribute(geometry, 'position');
      toLocal.copy(mesh.matrixWorld).invert();
      for (let i = 0; i < position.count; i++) {
        const v = this.vertexMap[offset + i];
        world.set(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]).applyMatrix4(toLocal);
        position.setXYZ(i, world.x, world.y, world.z);
      }
      position.needsUpdate = true;
      // Tangents follow the old shape; without them three.js and other
      // viewers derive them from the UVs.
      geometry.deleteAttribute('tangent');
      if (normals && geometry.getAttribute('normal')) this.#writeNormals(mesh, offset, welded, normalToLocal);
      // Bounds with the normals: a live frame keeps the last ones (two more
      // passes over the vertices; the view only culls by them).
      if (normals) {
        geometry.computeBoundingBox();
        geometry.computeBoundingSphere();
        // A skinned mesh is culled by bounds of its own (the skinned shape's), computed once.
        if (mesh.isSkinnedMesh) {
          mesh.computeBoundingBox();
          mesh.computeBoundingSphere();
        }
      }
    }
  }

  #writeNormals(mesh, offset, welded, normalToLocal) {
    const geometry = mesh.geometry;
    floatAttribute(geometry, 'normal');
    geometry.computeVertexNormals(); // each side of a hard edge its own
    const normal = geometry.getAttribute('normal');
    // A world normal n comes back into the node's frame as M^T n (normalised):
    // the inverse of the normal matrix (M^-1)^T.
    normalToLocal.setFromMatrix4(mesh.matrixWorld).transpose();
    const n = new Vector3();
    for (let i = 0; i < normal.count; i++) {
      const v = this.vertexMap[offset + i];
      if (!this.#smooth[v]) continue;
      n.set(welded[3 * v], welded[3 * v + 1], welded[3 * v + 2]).applyMatrix3(normalToLocal).normalize();
      // A mirroring node turns the merged triangles' winding: keep the side
      // the primitive's own normal is on.
      const side = n.x * normal.getX(i) + n.y * normal.getY(i) + n.z * normal.getZ(i);
      if (side < 0) n.negate();
      normal.setXYZ(i, n.x, n.y, n.z);
    }
    normal.needsUpdate = true;
  }

  // 1 for the solver vertices whose copies in the file all have the same
  // normal (or no normal): a smooth surface, one normal on export.
  #smoothVertices(weldedCount) {
    const smooth = new Uint8Array(weldedCount).fill(1);
    const first = new Float32Array(weldedCount * 3);
    const seen = new Uint8Array(weldedCount);
    const n = new Vector3();
    const normalMatrix = new Matrix3();
    for (const { mesh, offset } of this.parts) {
      const normal = mesh.geometry.getAttribute('normal');
      if (!normal) continue;
      normalMatrix.getNormalMatrix(mesh.matrixWorld);
      for (let i = 0; i < normal.count; i++) {
        const v = this.vertexMap[offset + i];
        n.fromBufferAttribute(normal, i).applyMatrix3(normalMatrix).normalize();
        if (!seen[v]) {
          seen[v] = 1;
          first.set([n.x, n.y, n.z], 3 * v);
        } else if (n.x * first[3 * v] + n.y * first[3 * v + 1] + n.z * first[3 * v + 2] < SAME_NORMAL_COS) {
          smooth[v] = 0;
        }
      }
    }
    return smooth;
  }
}

// The geometry's attribute `name` as 32-bit floats, replaced by a float copy
// where the file quantized it (KHR_mesh_quantization, meshopt): an edited
// shape leaves the quantization's range (normalized values clamp at 1), and
// the normals are summed in place before they are normalized.
function floatAttribute(geometry, name) {
  const attribute = geometry.getAttribute(name);
  if (attribute.array instanceof Float32Array) return attribute;
  const copy = new BufferAttribute(new Float32Array(attribute.count * attribute.itemSize), attribute.itemSize);
  for (let i = 0; i < attribute.count; i++) {
    for (let c = 0; c < attribute.itemSize; c++) copy.setComponent(i, c, attribute.getComponent(i, c));
  }
  geometry.setAttribute(name, copy);
  return copy;
}
