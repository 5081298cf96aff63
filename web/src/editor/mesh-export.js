// The committed mesh as a file: OBJ, PLY (binary) and STL (binary) by the
// core's writers in the worker (the CLI writes the same), GLB by three.js,
// since the core has no glTF writer: a mesh loaded from a glTF file goes back
// into its own scene, with its materials, UVs and nodes (io/gltf-source.js);
// any other with what its file carried that glTF has a place for: an OBJ's
// texture coordinates and material names, an OBJ's or a PLY's vertex
// colours (io/export-mesh.js).
import { exportGlb } from '../io/export-mesh.js';
import { CORE_EXPORT_FORMATS, EXPORT_FORMATS } from '../io/mesh-formats.js';
import { Request } from '../worker/protocol.js';
import { badParameter } from '../shared/errors.js';

/** @returns {Promise<ArrayBuffer>} */
export async function exportMeshFile(client, document, format) {
  if (!EXPORT_FORMATS.includes(format)) {
    throw badParameter(`export format must be one of ${EXPORT_FORMATS.join(', ')}, got '${format}'`);
  }
  if (!CORE_EXPORT_FORMATS.includes(format)) {
    if (document.gltf) return document.gltf.exportGlb(document.positions, document.triangles);
    const baseName = document.name.replace(/\.[^.]+$/, '') || 'anisoform';
    const surface = await client.request(Request.surfaceAttributes, {});
    return exportGlb(document.positions, document.triangles, baseName, surface);
  }
  const { bytes } = await client.request(Request.exportMesh, { format });
  return bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
}
