// File panel: open a mesh or saved edits (picker; drag-and-drop is in
// drop-zone.js), export the current mesh, save the edits (the edit document)
// as a file, and reset to the mesh as loaded.
import { downloadBytes } from '../io/download.js';
import { EXPORT_FORMATS } from '../io/mesh-formats.js';
import { OPEN_ACCEPT_ATTRIBUTE, openFiles, savedEditsName } from '../io/open-files.js';
import { h, section } from './dom.js';

/**
 * askToReplace(message) -> Promise<'save'|'open'|'cancel'> (replace-dialog.js)
 * is asked before an open replaces edits made.
 */
export function filePanel({ api, editor, reportError, askToReplace }) {
  const saveEdits = () => {
    try {
      const json = `${JSON.stringify(api.document(), null, 1)}\n`;
      downloadBytes(new TextEncoder().encode(json), savedEditsName(editor.document.name), 'application/json');
    } catch (error) {
      reportError(error, 'The edits were not saved');
    }
  };
  // Opening a mesh or saved edits starts new work, which Undo cannot take
  // back: with edits made, the user chooses (saving them first, or not).
  const mayReplace = async (names) => {
    const count = editor.ops.document?.ops.length ?? 0;
    if (count === 0) return true;
    const answer = await askToReplace(`Opening ${names} replaces the ${count} edit${count === 1 ? '' : 's'} of ` +
      `${editor.document.name}: Undo cannot bring ${count === 1 ? 'it' : 'them'} back.`);
    if (answer === 'save') saveEdits();
    return answer !== 'cancel';
  };
  const input = h('input', {
    type: 'file',
    id: 'file-input',
    accept: OPEN_ACCEPT_ATTRIBUTE,
    multiple: true,
    className: 'visually-hidden',
    'data-testid': 'file-input',
    onchange: () => {
      const files = [...(input.files ?? [])];
      input.value = ''; // choosing the same file again still opens it
      if (files.length > 0) openFiles(api, files, { mayReplace }).catch((error) => reportError(error, 'Nothing was opened'));
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
  const saveButton = h('button', {
    className: 'button',
    'data-testid': 'save-edits',
    title: 'The edits as a file (JSON) to open again later with the mesh: Open… both, or drop both on the view',
    onclick: saveEdits,
  }, 'Save edits');
  const resetButton = h('button', {
    className: 'button',
    'data-testid': 'reset',
    onclick: () => api.reset(),
  }, 'Reset');
  const fileName = h('p', { className: 'file-name' });
  editor.on('mesh', (document) => (fileName.textContent = document.name));
  // Nothing to save, and nothing to reset, until an edit is made.
  const syncSave = () => {
    const edited = editor.ops.document?.ops.length > 0;
    saveButton.disabled = !edited;
    resetButton.disabled = !edited;
    resetButton.title = edited ? 'Back to the mesh as loaded (undoable)' : 'No edits to reset: this is the mesh as loaded';
  };
  syncSave();
  editor.on('document', syncSave);
  editor.on('mesh', syncSave);

  return {
    element: section(
      'Mesh',
      fileName,
      h('div', { className: 'row' }, input, h('label', { className: 'button button-primary', for: 'file-input' }, 'Open…'), resetButton),
      h('p', { className: 'hint' }, 'OBJ, PLY, STL, OFF or GLB — or drop a file on the view. Saved edits (.json): open or drop them with their mesh.'),
      h('div', { className: 'row' }, format, exportButton, saveButton),
    ),
    // The keys' actions (Ctrl+O, Ctrl+S: editing-keys.js), as the buttons do them.
    open: () => input.click(),
    /** Whether files dropped may replace the work (drop-zone.js): as the picker asks. */
    mayReplace,
    // Before the first edit the button is disabled; the key says why instead of nothing.
    save: () => {
      if (!saveButton.disabled) saveButton.click();
      else editor.emit('notice', { message: 'No edits to save yet: Save edits keeps the edits once one is made (Export saves the mesh).', source: 'save' });
    },
  };
}
