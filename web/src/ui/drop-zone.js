// Drag-and-drop upload anywhere on the page: an overlay while a file hovers,
// the first dropped file is loaded.
export function installDropZone(overlay, { api, reportError }) {
  let depth = 0; // dragenter/dragleave fire for every child element
  const hasFiles = (event) => [...(event.dataTransfer?.types ?? [])].includes('Files');
  window.addEventListener('dragenter', (event) => {
    if (!hasFiles(event)) return;
    depth++;
    overlay.hidden = false;
  });
  window.addEventListener('dragleave', () => {
    depth = Math.max(0, depth - 1);
    if (depth === 0) overlay.hidden = true;
  });
  window.addEventListener('dragover', (event) => {
    if (hasFiles(event)) event.preventDefault(); // allows the drop
  });
  window.addEventListener('drop', (event) => {
    if (!hasFiles(event)) return;
    event.preventDefault();
    depth = 0;
    overlay.hidden = true;
    const file = event.dataTransfer.files[0];
    if (file) api.load(file, file.name).catch(reportError); // the editor has shown it already
  });
}
