// Keeps the direction glyphs in step with the editor: the field of the
// current direction source (the Flatten panel's in flatten mode) over the selection (asked from the worker's
// directionField), and the placed arrows. Glyphs hide during a live drag,
// where they would float off the moving surface, and refresh after it.
import { DirectionMissingError, directionFromSettings, flattenDirectionFromSettings } from '../tools/direction-source.js';
import { DirectionGlyphs } from './direction-glyphs.js';

const REFRESH_DELAY_MS = 60;
// Error codes (aniso::error_code_name) of a direction the core declines to build.
const SOLVER_REFUSALS = ['bad-parameter', 'bad-mesh', 'numerical'];

export class DirectionDisplay {
  #timer = null;
  #request = 0;

  constructor({ editor, settings, viewer, meshView, lifetime }) {
    lifetime.defer(() => clearTimeout(this.#timer));
    this.editor = editor;
    this.settings = settings;
    this.meshView = meshView;
    this.fieldGlyphs = new DirectionGlyphs(viewer, { color: 0x7fe3ff });
    this.arrowGlyphs = new DirectionGlyphs(viewer, { color: 0xffd54a, maxGlyphs: 512 });

    settings.on('change', ({ section }) => {
      if (['direction', 'arrows', 'lastScreen', 'display', 'mode', 'flatten'].includes(section)) this.schedule();
    });
    editor.on('mesh', () => this.schedule());
    editor.on('positions', ({ live }) => !live && this.schedule());
    editor.on('selection', ({ live }) => !live && this.schedule());
    editor.on('gesture', (active) => (active ? this.#hideAll() : this.schedule()));
  }

  schedule() {
    clearTimeout(this.#timer);
    this.#timer = setTimeout(() => this.refresh(), REFRESH_DELAY_MS);
  }

  #hideAll() {
    this.#request++;
    this.fieldGlyphs.hide();
    this.arrowGlyphs.hide();
  }

  async refresh() {
    const document = this.editor.document;
    const values = this.settings.values;
    if (!document || !values.display.glyphs || this.editor.gestureActive) {
      this.#hideAll();
      return;
    }
    this.showArrows(values.arrows);
    let direction;
    try {
      direction = values.mode === 'flatten' ? flattenDirectionFromSettings(values, document.bounds())
        : directionFromSettings(values);
    } catch (error) {
      this.fieldGlyphs.hide(); // no direction yet (no drag, no arrows): nothing to draw
      if (!(error instanceof DirectionMissingError)) this.editor.report(error, 'The direction glyphs could not be drawn');
      return;
    }
    const request = ++this.#request;
    try {
      const field = await this.editor.directionField(direction);
      if (request !== this.#request || !field || this.editor.document !== document) return;
      this.fieldGlyphs.show({
        directions: field,
        positions: this.meshView.displayedPositions,
        normals: this.meshView.normals,
        weights: document.selectionCount > 0 ? document.selection : null,
        length: document.bounds().diagonal * 0.03,
      });
    } catch (error) {
      // A direction the solver cannot build here (e.g. curvature on a flat
      // patch) fails the edit too, which reports it; the glyphs just stay
      // hidden. Anything else is a fault the user must hear of.
      this.fieldGlyphs.hide();
      if (!SOLVER_REFUSALS.includes(error?.code)) this.editor.report(error, 'The direction glyphs could not be drawn');
    }
  }

  /** Draws arrows [{vertex, direction}] (also used live while placing one). */
  showArrows(arrows) {
    const document = this.editor.document;
    if (!document || arrows.length === 0 || !this.settings.values.display.glyphs) {
      this.arrowGlyphs.hide();
      return;
    }
    const directions = new Float32Array(document.vertexCount * 3);
    for (const { vertex, direction } of arrows) directions.set(direction, 3 * vertex);
    this.arrowGlyphs.show({
      directions,
      positions: this.meshView.displayedPositions,
      normals: this.meshView.normals,
      weights: null,
      vertices: arrows.map(({ vertex }) => vertex),
      length: document.bounds().diagonal * 0.08,
    });
  }
}
