// The view of the autosaved work: the selection, the tool and its settings
// (amounts, direction source, method, iterations, brush...) and the camera,
// kept beside the work of the tab (autosave.js) and put back after a reload
// restored that work. A reload used to bring back the mesh and the edits
// only: the selected region, the tool, its amounts and the view were gone.
//
// A view goes with the work it was made on: the settings and the camera
// are put back when the base mesh is the one they were saved with (its
// name, size and hash), the selection only when the whole document is too
// and every edit of it was put back (a restore stopped with Esc, or failed,
// shows other work: the selection saved then is not applied to it).
import { sameDocument } from './edit-document.js';

// Saved once the view has been still this long: an orbit changes the camera at every frame.
const SAVE_AFTER_MS = 250;

export class ViewAutosave {
  #editor;
  #settings;
  #viewer;
  #lifetime;
  #timer = 0;
  #saving = false;

  constructor({ editor, settings, viewer, lifetime }) {
    this.#editor = editor;
    this.#settings = settings;
    this.#viewer = viewer;
    this.#lifetime = lifetime;
    lifetime.defer(() => clearTimeout(this.#timer));
  }

  /**
   * Puts back `restored.view` (DocumentPersistence.restoreAutosave's
   * {complete, view}) on the work now shown, as far as it goes with it.
   */
  apply({ complete, view }) {
    const document = this.#editor.document;
    const work = document && this.#editor.ops.toJSON();
    if (!view || !work || !sameMesh(view.work?.mesh, work.mesh)) return;
    this.#settings.restore(view.settings);
    if (cameraSeesMesh(view.camera, document.bounds())) this.#viewer.setView(view.camera);
    const weights = view.selection;
    if (complete && weights instanceof Float32Array && weights.length === document.vertexCount && sameDocument(view.work, work)
      && weights.every((weight) => weight >= 0 && weight <= 1)) {
      this.#editor.selectionState.restore(weights.slice());
    }
  }

  /** From now on, every change of the view is saved (once the work shown is the page's: after its restore). */
  start() {
    if (this.#saving || this.#lifetime.disposed) return;
    this.#saving = true;
    const soon = () => this.#saveSoon();
    this.#editor.on('selection', ({ live }) => !live && soon());
    this.#editor.on('document', soon);
    this.#settings.on('change', soon);
    this.#viewer.controls.addEventListener('change', soon);
    this.#lifetime.defer(() => this.#viewer.controls.removeEventListener('change', soon));
    // A tab reloaded within SAVE_AFTER_MS of the last change still saves it.
    this.#lifetime.listen(window, 'pagehide', () => this.#saveNow({ leaving: true }));
  }

  #saveSoon() {
    clearTimeout(this.#timer);
    this.#timer = setTimeout(() => this.#saveNow(), SAVE_AFTER_MS);
  }

  #saveNow({ leaving = false } = {}) {
    clearTimeout(this.#timer);
    const document = this.#editor.document;
    if (!document || this.#lifetime.disposed) return;
    const view = {
      work: this.#editor.ops.toJSON(),
      settings: this.#settings.snapshot(),
      selection: document.selectionCount > 0 ? document.selection.slice() : null,
      camera: this.#viewer.view(),
      savedAt: Date.now(),
    };
    // A view that cannot be stored is not said: the work's own save, which
    // meets the same storage, says it (autosave.js), and a lost view costs
    // a click, not work.
    this.#editor.ops.saveView(view, { leaving }).catch(() => {});
  }
}

// A stored camera is put back only where the mesh can be seen from it: its
// target within a few sizes of the mesh, at a distance between a ten-
// thousandth and a thousand sizes (a record edited or damaged put the camera
// at 1e30, or inside the mesh on its target). The viewer refuses what is not
// a camera at all (setView).
function cameraSeesMesh(camera, { center, diagonal }) {
  const point = (value) => Array.isArray(value) && value.length === 3;
  if (!camera || !point(camera.position) || !point(camera.target) || !(diagonal > 0)) return false;
  const distance = (a, b) => Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
  const away = distance(camera.position, camera.target);
  return distance(camera.target, center) <= 10 * diagonal && away >= 1e-4 * diagonal && away <= 1e3 * diagonal;
}

function sameMesh(a, b) {
  return Boolean(a && b) && a.name === b.name && a.vertices === b.vertices && a.triangles === b.triangles && a.hash === b.hash;
}
