// What the user opens (the Open… picker, or files dropped on the view): a
// mesh is loaded; saved edits (the edit document as the Save edits button
// writes it, .json) are replayed on the mesh loaded, or on the mesh file
// opened with them, through the same api.load and api.open as embedders use.
import { badParameter } from '../shared/errors.js';
import { ACCEPT_ATTRIBUTE } from './mesh-formats.js';

export const SAVED_EDITS_EXTENSION = '.json';
/** The picker's `accept`: the meshes and saved edits. */
export const OPEN_ACCEPT_ATTRIBUTE = `${ACCEPT_ATTRIBUTE},${SAVED_EDITS_EXTENSION}`;

const isSavedEdits = (file) => file.name.toLowerCase().endsWith(SAVED_EDITS_EXTENSION);

/** The file name saved edits of the mesh `meshName` are offered under. */
export function savedEditsName(meshName) {
  return `${meshName.replace(/\.[^.]+$/, '')}-edits${SAVED_EDITS_EXTENSION}`;
}

/**
 * Loads or replays `files` (an array of File). Rejects when nothing could be
 * opened: api.load's and api.open's errors are reported already, the others
 * (a wrong set of files, a file that is not JSON) are the caller's to report.
 * `mayReplace(names)` is asked first (the page asks the user when there are
 * edits, and may save them): it resolves false to open nothing.
 */
export async function openFiles(api, files, { mayReplace = async () => true } = {}) {
  const edits = files.filter(isSavedEdits);
  const meshes = files.filter((file) => !isSavedEdits(file));
  if (files.length === 0 || edits.length > 1 || meshes.length > 1) {
    throw badParameter(
      `open one mesh, or saved edits (${SAVED_EDITS_EXTENSION}) alone or with the mesh they were made on; ` +
        `got ${files.length === 0 ? 'no file' : files.map((file) => file.name).join(', ')}`,
    );
  }
  // A file that is not saved edits is refused before the user is asked.
  const document = edits.length === 0 ? null : parseSavedEdits(edits[0].name, await edits[0].text());
  if (!(await mayReplace(files.map((file) => file.name).join(' and ')))) return;
  if (!document) return api.load(meshes[0], meshes[0].name);
  if (meshes.length === 0) return api.open(document);
  return api.open(document, new Uint8Array(await meshes[0].arrayBuffer()), meshes[0].name);
}

function parseSavedEdits(fileName, text) {
  try {
    return JSON.parse(text);
  } catch (error) {
    throw badParameter(`${fileName} is not saved edits (an edit document in JSON): ${error.message}`);
  }
}
