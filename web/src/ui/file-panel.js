// File panel: open a mesh (picker; drag-and-drop is in drop-zone.js), export
// the current mesh, and reset to the mesh as loaded.
import { downloadBytes } from '../io/download.js';
import { ACCEPT_ATTRIBUTE, EXPORT_FORMATS } from '../io/mesh-formats.js';
import { h, section } from './dom.js';

export function filePanel({ api, editor, reportError }) {
  const input = h('input', {
    type: 'file',
    id: 'file-input',
    accept: ACCEPT_ATTRIBUTE,
    className: 'visually-hidden',
    'data-testid': 'file-input',
    onchange: () => {
      const file = input.files?.[0];
      input.value = ''; // choosing the same file again still loads it
      if (file) api.load(file, file.name).catch(reportError); // the editor has shown it already
    },
  });
  const format = h(
    'select',
    { id: 'export-format', 'aria-label': 'Export format' },
    EXPORT_FORMATS.map((name) => h('option', { value: name }, name.toUpperCase())),
  );
  const exportButton = h('button', {
    className: 'button',
    'data-testid': 'export',
    onclick: async () => {
      const bytes = await api.export(format.value).catch((error) => {
        reportError(error);
        return null;
      });
      if (!bytes) return;
      const baseName = (editor.document?.name ?? 'anisoform').replace(/\.[^.]+$/, '');
      downloadBytes(bytes, `${baseName}-edited.${format.value}`);
    },
  }, 'Export');
  const resetButton = h('button', {
    className: 'button',
    'data-testid': 'reset',
    title: 'Back to the mesh as loaded (undoable)',
    onclick: () => api.reset(),
  }, 'Reset');
  const fileName = h('p', { className: 'file-name' });
  editor.on('mesh', (document) => (fileName.textContent = document.name));

  return section(
    'Mesh',
    fileName,
    h('div', { className: 'row' }, input, h('label', { className: 'button button-primary', for: 'file-input' }, 'Open…'), resetButton),
    h('p', { className: 'hint' }, 'OBJ, PLY, STL, OFF or GLB — or drop a file on the view.'),
    h('div', { className: 'row' }, format, exportButton),
  );
}
