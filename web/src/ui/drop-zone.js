// Drag-and-drop upload anywhere on the modeller (`target`: its root element,
// or the window for the standalone site): an overlay while a file hovers, the
// first dropped file is loaded.
export function installDropZone(target, overlay, { api, reportError, lifetime }) {
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
    const file = event.dataTransfer.files[0];
    if (file) api.load(file, file.name).catch(reportError); // the editor has shown it already
  });
}
