// Keeps the direction glyphs in step with the editor: the field of the
// current direction source (the Flatten panel's in flatten mode) over the selection (asked from the worker's
// directionField), and the placed arrows. Glyphs hide during a live drag,
// where they would float off the moving surface, and refresh after it.
//
// Field glyphs are about FIELD_SPACING_PX apart on screen (a grid of that
// size at the orbit target's distance), redrawn when a zoom changes that by
// a quarter; arrows are solid, with heads, in a blue that stands out on the
// orange selection and the grey surface. The canvas's data-field-glyphs and
// data-arrow-glyphs say how many are drawn.
import { DirectionMissingError, directionFromSettings, flattenDirectionFromSettings } from '../tools/direction-source.js';
import { DirectionGlyphs } from './direction-glyphs.js';

const REFRESH_DELAY_MS = 60;
const FIELD_SPACING_PX = 26;
const ARROW_COLOR = 0x2f5bff;
// Error codes (aniso::error_code_name) of a direction the core declines to build.
const SOLVER_REFUSALS = ['bad-parameter', 'bad-mesh', 'numerical'];

export class DirectionDisplay {
  #timer = null;
  #request = 0;
  #spacingShown;

  constructor({ editor, settings, viewer, meshView, lifetime }) {
    lifetime.defer(() => clearTimeout(this.#timer));
    this.editor = editor;
    this.settings = settings;
    this.meshView = meshView;
    this.viewer = viewer;
    this.fieldGlyphs = new DirectionGlyphs(viewer, { color: 0x7fe3ff });
    this.arrowGlyphs = new DirectionGlyphs(viewer, { color: ARROW_COLOR, maxGlyphs: 512, kind: 'arrow' });
    this.#spacingShown = 0;
    // A zoom that changes the field's screen spacing by a quarter redraws it.
    lifetime.defer(viewer.on('frame', () => {
      if (!this.fieldGlyphs.count) return;
      const ratio = this.#spacing() / this.#spacingShown;
      if (ratio > 1.25 || ratio < 0.8) this.schedule();
    }));

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
    this.#syncCounts();
  }

  #syncCounts() {
    const dataset = this.viewer.canvas.dataset;
    dataset.fieldGlyphs = String(this.fieldGlyphs.count);
    dataset.arrowGlyphs = String(this.arrowGlyphs.count);
  }

  // FIELD_SPACING_PX in model units at the orbit target's distance.
  #spacing() {
    const { camera, controls, canvas } = this.viewer;
    const distance = camera.position.distanceTo(controls.target);
    const visibleHeight = 2 * distance * Math.tan((camera.fov * Math.PI) / 360);
    return (FIELD_SPACING_PX * visibleHeight) / Math.max(1, canvas.clientHeight);
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
      this.#syncCounts();
      if (!(error instanceof DirectionMissingError)) this.editor.report(error, 'The direction glyphs could not be drawn');
      return;
    }
    const request = ++this.#request;
    try {
      const field = await this.editor.directionField(direction);
      if (request !== this.#request || !field || this.editor.document !== document) return;
      const spacing = this.#spacing();
      this.#spacingShown = spacing;
      this.fieldGlyphs.show({
        directions: field,
        positions: this.meshView.displayedPositions,
        normals: this.meshView.normals,
        weights: document.selectionCount > 0 ? document.selection : null,
        length: Math.min(0.7 * spacing, document.bounds().diagonal * 0.03),
        spacing,
      });
      this.#syncCounts();
    } catch (error) {
      // A direction the solver cannot build here (e.g. curvature on a flat
      // patch) fails the edit too, which reports it; the glyphs just stay
      // hidden. Anything else is a fault the user must hear of.
      this.fieldGlyphs.hide();
      this.#syncCounts();
      if (!SOLVER_REFUSALS.includes(error?.code)) this.editor.report(error, 'The direction glyphs could not be drawn');
    }
  }

  /** Draws arrows [{vertex, direction}] (also used live while placing one). */
  showArrows(arrows) {
    const document = this.editor.document;
    if (!document || arrows.length === 0 || !this.settings.values.display.glyphs) {
      this.arrowGlyphs.hide();
      this.#syncCounts();
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
      length: document.bounds().diagonal * 0.12,
    });
    this.#syncCounts();
  }
}
