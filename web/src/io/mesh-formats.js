// Which reader handles which file.
//
// OBJ, OFF, PLY and STL go to the core's readers in the worker as raw bytes:
// they triangulate polygons, weld STL soups and name the exact face, vertex or
// line at fault in a malformed file, and the same readers serve the CLI.
// GLB (and self-contained .gltf) go through three.js's GLTFLoader on the page,
// because the core has no glTF reader; the triangles are then handed to the
// worker with session.setMesh.
export const CORE_FORMATS = ['obj', 'off', 'ply', 'stl'];
export const GLTF_FORMATS = ['glb', 'gltf'];
export const EXPORT_FORMATS = ['obj', 'ply', 'stl', 'glb'];
// Written by the core's writers in the worker (the CLI's too); GLB by three.js.
export const CORE_EXPORT_FORMATS = ['obj', 'ply', 'stl'];
export const ACCEPT_ATTRIBUTE = [...CORE_FORMATS, ...GLTF_FORMATS].map((ext) => `.${ext}`).join(',');

export class UnsupportedFormatError extends Error {
  constructor(message) {
    super(message);
    this.name = 'UnsupportedFormatError';
    this.code = 'bad-file';
  }
}

/** 'core' or 'gltf' for a file name; throws UnsupportedFormatError otherwise. */
export function readerFor(fileName) {
  const extension = extensionOf(fileName);
  if (CORE_FORMATS.includes(extension)) return 'core';
  if (GLTF_FORMATS.includes(extension)) return 'gltf';
  const what = extension ? `'.${extension}' files` : `'${fileName}' (no file extension)`;
  throw new UnsupportedFormatError(
    `Anisoform cannot read ${what}. Supported: OBJ, PLY, STL, OFF and GLB.`,
  );
}

export function extensionOf(fileName) {
  const match = /\.([^./\\]+)$/.exec(fileName ?? '');
  return match ? match[1].toLowerCase() : '';
}
