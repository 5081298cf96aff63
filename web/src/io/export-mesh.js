// Export of the current mesh as GLB, with three.js's GLTFExporter: the core
// has no glTF writer (OBJ, PLY and STL are the core's, in the worker; see
// Editor.export). The mesh is rebuilt with positions, vertex normals and the
// index only, so editor-only attributes (selection, heat map) never leak out.
import { BufferAttribute, BufferGeometry, Mesh, MeshStandardMaterial } from 'three';
import { GLTFExporter } from 'three/addons/exporters/GLTFExporter.js';

/** @returns {Promise<ArrayBuffer>} */
export async function exportGlb(positions, triangles, name = 'anisoform') {
  const geometry = new BufferGeometry();
  geometry.setAttribute('position', new BufferAttribute(new Float32Array(positions), 3));
  geometry.setIndex(new BufferAttribute(new Uint32Array(triangles), 1));
  geometry.computeVertexNormals();
  const mesh = new Mesh(geometry, new MeshStandardMaterial());
  mesh.name = name;
  try {
    return await new GLTFExporter().parseAsync(mesh, { binary: true });
  } finally {
    geometry.dispose();
    mesh.material.dispose();
  }
}
