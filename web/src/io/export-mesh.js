// Export of the current mesh with three.js's exporters: OBJ (text, indexed),
// PLY (binary, indexed), STL (binary; STL has no index, readers weld it) and
// GLB (indexed). The mesh is rebuilt with positions, vertex normals and the
// index only, so editor-only attributes (selection, heat map) never leak out.
import { BufferAttribute, BufferGeometry, Mesh, MeshStandardMaterial } from 'three';
import { GLTFExporter } from 'three/addons/exporters/GLTFExporter.js';
import { OBJExporter } from 'three/addons/exporters/OBJExporter.js';
import { PLYExporter } from 'three/addons/exporters/PLYExporter.js';
import { STLExporter } from 'three/addons/exporters/STLExporter.js';
import { EXPORT_FORMATS } from './mesh-formats.js';

/** @returns {Promise<ArrayBuffer>} */
export async function exportMesh(format, positions, triangles, name = 'anisoform') {
  if (!EXPORT_FORMATS.includes(format)) {
    throw Object.assign(new Error(`export format must be one of ${EXPORT_FORMATS.join(', ')}, got '${format}'`), {
      code: 'bad-parameter',
    });
  }
  const geometry = new BufferGeometry();
  geometry.setAttribute('position', new BufferAttribute(new Float32Array(positions), 3));
  geometry.setIndex(new BufferAttribute(new Uint32Array(triangles), 1));
  geometry.computeVertexNormals();
  const mesh = new Mesh(geometry, new MeshStandardMaterial());
  mesh.name = name;
  try {
    switch (format) {
      case 'obj':
        return new TextEncoder().encode(new OBJExporter().parse(mesh)).buffer;
      case 'ply':
        return await new Promise((resolve) => new PLYExporter().parse(mesh, resolve, { binary: true, littleEndian: true }));
      case 'stl': {
        const view = new STLExporter().parse(mesh, { binary: true });
        return view.buffer.slice(view.byteOffset, view.byteOffset + view.byteLength);
      }
      case 'glb':
        return await new GLTFExporter().parseAsync(mesh, { binary: true });
    }
  } finally {
    geometry.dispose();
    mesh.material.dispose();
  }
}
