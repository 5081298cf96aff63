// Reading a mesh into the solver: the bytes of a File, Blob or ArrayBuffer go
// to the core's readers (OBJ, OFF, PLY, STL) in the worker, or through the
// glTF importer (GLB) and then to the worker as arrays. The worker checks and
// keeps the mesh; the page gets its MeshPayload (protocol.js).
import { importGltf } from '../io/import-gltf.js';
import { readerFor } from '../io/mesh-formats.js';
import { readFileBytes } from '../io/read-file.js';
import { Request } from '../worker/protocol.js';
import { badParameter } from '../shared/errors.js';

/**
 * @param {import('../worker/solver-client.js').SolverClient} client
 * @param {(progress: object) => void} emitProgress
 * @returns {Promise<import('../worker/protocol.js').MeshPayload>}
 */
export async function readMesh(client, source, name, emitProgress) {
  if (readerFor(name) === 'core') {
    // The worker reads a picked File and keeps the bytes as a Blob: on the
    // page, reading a 30 MB file and copying it into a Blob held the main
    // thread 100-200 ms at a time.
    if (source instanceof Blob) startReadProgress(name, emitProgress);
    else source = copyOf(source);
    return client.request(Request.loadFile, { source, name }, source instanceof ArrayBuffer ? [source] : []);
  }
  const bytes = source instanceof Blob ? await readFileBytes(source, startReadProgress(name, emitProgress)) : copyOf(source);
  emitProgress({ stage: 'parse', message: `Reading ${name}` });
  // The edit document's base mesh travels beside it (autosave) as a Blob:
  // IndexedDB stores a Blob's bytes off the main thread, where an ArrayBuffer
  // is cloned in the saving task (194 ms for a 30 MB file, at every autosave).
  const sourceBytes = source instanceof Blob ? source : new Blob([bytes]);
  const { positions, triangles, notes, source: scene } = await importGltf(bytes, name);
  // glTF splits vertices at seams; welding exact duplicates joins the surface.
  const payload = await client.request(Request.setMesh, { positions, triangles, weld: true }, [
    positions.buffer,
    triangles.buffer,
  ]);
  payload.info.notes = [...notes, ...(payload.info.notes ?? [])];
  scene.attach(payload.inputVertexMap, payload.info.vertices);
  return { ...payload, sourceBytes, gltf: scene };
}

const isBytes = (source) => source instanceof Blob || source instanceof ArrayBuffer || ArrayBuffer.isView(source);

/** The file name load() was given, or the File's own; refused when there is none, or nothing to read. */
export function fileNameOf(source, name) {
  if (!isBytes(source)) {
    const what = source === null ? 'null' : Array.isArray(source) ? 'an array' : `${typeof source === 'object' ? 'an' : 'a'} ${typeof source}`;
    throw badParameter(`load() takes a File, Blob, ArrayBuffer or typed array (or, in a modeller, a URL); got ${what}`);
  }
  if (typeof name === 'string' && name) return name;
  name = source?.name ?? '';
  if (!name) throw badParameter('load() needs a file name with its extension, e.g. "part.stl"');
  return name;
}

// The bytes of an ArrayBuffer or typed array source, copied: the caller keeps theirs.
function copyOf(source) {
  if (source instanceof ArrayBuffer) return source.slice(0);
  return source.buffer.slice(source.byteOffset, source.byteOffset + source.byteLength); // a typed array (fileNameOf checked)
}

// Shows the read at 0 % at once; the worker (or the page, for a GLB) moves it.
function startReadProgress(name, emitProgress) {
  const report = (fraction) => emitProgress({ stage: 'read', message: `Reading ${name}`, fraction });
  report(0);
  return report;
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
