// Reading a mesh into the solver: the bytes of a File, Blob or ArrayBuffer go
// to the core's readers (OBJ, OFF, PLY, STL) in the worker, or through the
// glTF importer (GLB) and then to the worker as arrays. The worker checks and
// keeps the mesh; the page gets its MeshPayload (protocol.js).
import { importGltf } from '../io/import-gltf.js';
import { readerFor } from '../io/mesh-formats.js';
import { readFileBytes } from '../io/read-file.js';
import { Request } from '../worker/protocol.js';

/**
 * @param {import('../worker/solver-client.js').SolverClient} client
 * @param {(progress: object) => void} emitProgress
 * @returns {Promise<import('../worker/protocol.js').MeshPayload>}
 */
export async function readMesh(client, source, name, emitProgress) {
  const reader = readerFor(name);
  const bytes = await bytesOf(source, name, emitProgress);
  emitProgress({ stage: 'parse', message: `Reading ${name}` });
  // The edit document's base mesh travels beside it (autosave): keep the
  // file's bytes, as a Blob: IndexedDB stores a Blob's bytes off the main
  // thread, where an ArrayBuffer is cloned in the saving task (194 ms for a
  // 30 MB file, at every autosave).
  const sourceBytes = new Blob([bytes]);
  if (reader === 'core') return { ...(await client.request(Request.loadFile, { bytes, name }, [bytes])), sourceBytes };
  const { positions, triangles, notes } = await importGltf(bytes, name);
  // glTF splits vertices at seams; welding exact duplicates joins the surface.
  const payload = await client.request(Request.setMesh, { positions, triangles, weld: true }, [
    positions.buffer,
    triangles.buffer,
  ]);
  payload.info.notes = [...notes, ...(payload.info.notes ?? [])];
  return { ...payload, sourceBytes };
}

/** The file name load() was given, or the File's own; refused when there is none. */
export function fileNameOf(source, name) {
  if (typeof name === 'string' && name) return name;
  name = source?.name ?? '';
  if (!name) throw Object.assign(new Error('load() needs a file name with its extension, e.g. "part.stl"'), { code: 'bad-parameter' });
  return name;
}

async function bytesOf(source, name, emitProgress) {
  if (source instanceof ArrayBuffer) return source.slice(0); // the caller keeps theirs
  if (ArrayBuffer.isView(source)) return source.buffer.slice(source.byteOffset, source.byteOffset + source.byteLength);
  if (source instanceof Blob) {
    emitProgress({ stage: 'read', message: `Reading ${name}`, fraction: 0 });
    return readFileBytes(source, (fraction) => emitProgress({ stage: 'read', message: `Reading ${name}`, fraction }));
  }
  throw Object.assign(new Error('load() takes a File, Blob or ArrayBuffer'), { code: 'bad-parameter' });
}

// A load error in plain words: the core already names the file ("x.obj:
// ..."), and the context says it again, so the detail drops it; it also says
// that the mesh on screen stays.
export function loadError(error, name, current) {
  let detail = error?.message ?? String(error);
  for (const prefix of [`${name}: `, `'${name}': `]) {
    if (name && detail.startsWith(prefix)) detail = detail.slice(prefix.length);
  }
  detail = detail.replace(/\.?\s*$/, '.');
  if (current) detail += ` The current mesh (${current.name}) is unchanged.`;
  return Object.assign(new Error(detail), { code: error?.code ?? 'internal' });
}
