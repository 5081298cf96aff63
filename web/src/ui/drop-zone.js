// Drag-and-drop upload anywhere on the modeller (`target`: its root element,
// or the window for the standalone site): an overlay while a file hovers; the
// dropped files are opened as the Open… picker's are (a mesh, or saved edits
// with or without their mesh: io/open-files.js).
import { openFiles } from '../io/open-files.js';

export function installDropZone(target, overlay, { api, reportError, lifetime, mayReplace }) {
  let depth = 0; // dragenter/dragleave fire for every child element
  const hasFiles = (event) => [...(event.dataTransfer?.types ?? [])].includes('Files');
  lifetime.listen(target, 'dragenter', (event) => {
    if (!hasFiles(event)) return;
    depth++;
    overlay.hidden = false;
  });
  lifetime.listen(target, 'dragleave', () => {
    depth = Math.max(0, depth - 1);
    if (depth === 0) overlay.hidden = true;
  });
  lifetime.listen(target, 'dragover', (event) => {
    if (hasFiles(event)) event.preventDefault(); // allows the drop
  });
  lifetime.listen(target, 'drop', (event) => {
    if (!hasFiles(event)) return;
    event.preventDefault();
    depth = 0;
    overlay.hidden = true;
    const files = [...event.dataTransfer.files];
    if (files.length > 0) openFiles(api, files, { mayReplace }).catch((error) => reportError(error, 'Nothing was opened'));
  });
}
