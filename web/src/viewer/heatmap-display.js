// Keeps the heat map in step with what the view shows, when the Display panel
// turns it on: the core's distortion against the mesh as loaded (live
// previews included), or the compression error of the last flattening, on
// the same vertices the 2D pattern view colours by triangle, with its legend.
//
// The distortion is the core's (Session.distortion in the worker: the area
// ratio, or the principal stretch farthest from 1); this file only maps it to
// colours, through log2, so that twice and half look equally strong. Edits
// bring the values along with their positions (editor.heatMapKind), so the
// map follows every live-preview frame without a second request; other
// changes (a load, undo, the panel) ask the worker. The range at full colour
// is fixed or adapted to the values shown (Display panel; heat-palettes.js).
import { HEAT_PALETTES, heatRange } from './heat-palettes.js';
import { HeatmapLegend } from './heatmap-legend.js';

const DISTORTION_KINDS = ['area', 'stretch'];

export class HeatmapDisplay {
  #latest = 0; // the newest refresh: older worker answers are dropped

  /** fileLook: () => whether the file's own materials are drawn instead of the surface (gltf-display.js). */
  constructor({ editor, settings, meshView, viewport, lifetime, reportError, fileLook = () => false }) {
    this.editor = editor;
    this.settings = settings;
    this.meshView = meshView;
    this.reportError = reportError;
    this.fileLook = fileLook;
    this.legend = new HeatmapLegend(viewport, lifetime);
    settings.on('change', ({ section }) => section === 'display' && this.refresh());
    editor.on('mesh', () => this.refresh());
    editor.on('positions', ({ distortion }) => this.refresh(distortion));
    editor.on('pattern', () => this.refresh());
  }

  /** `distortion`: the core's values for the positions just shown, when an edit brought them. */
  refresh(distortion) {
    // Over the file's materials no heat map is drawn: neither its legend nor its values.
    const kind = this.fileLook() ? 'off' : this.settings.values.display.heatMap;
    const document = this.editor.document;
    const refresh = ++this.#latest;
    this.editor.heatMapKind = DISTORTION_KINDS.includes(kind) ? kind : null;
    this.meshView.setHeatMapVisible(kind !== 'off');
    if (kind === 'off' || !document) {
      this.legend.hide();
      return;
    }
    this.meshView.setHeatPalette(HEAT_PALETTES[kind]);
    if (kind === 'compression') {
      const pattern = this.editor.pattern;
      if (!pattern) {
        // No made-up 0-2 % scale over a plain surface: there is nothing to show yet.
        this.meshView.showDistortion(compressionValues(null, document.vertexCount));
        this.legend.showNothing(HEAT_PALETTES[kind], 'No pattern yet: flatten a patch (Flatten mode) to see its error here');
        return;
      }
      // The range from the triangles' errors, as the pattern pane takes it:
      // from the vertices' (their mean), the two legends said 2.5 % and 3.6 % for one pattern.
      this.#show(kind, compressionValues(pattern, document.vertexCount), pattern.compressionError);
      return;
    }
    if (distortion) {
      const values = log2Values(distortion);
      this.#show(kind, values, values);
      return;
    }
    this.editor.distortion(kind).then(
      (ratios) => {
        if (!ratios || refresh !== this.#latest) return;
        const values = log2Values(ratios);
        this.#show(kind, values, values);
      },
      (error) => this.reportError(error, 'The heat map could not be computed'),
    );
  }

  // `measured`: the values the range is taken from (for the compression
  // error, the patch's triangles only, not the zeros drawn outside it).
  #show(kind, values, measured) {
    const range = heatRange(kind, measured, this.settings.values.display.heatRange);
    this.meshView.setHeatRange(range.value);
    this.meshView.showDistortion(values);
    this.legend.show(HEAT_PALETTES[kind], range, kind === 'compression' ? formatError : formatRatio);
  }
}

const formatError = (error) => `${(100 * error).toFixed(error < 0.1 ? 1 : 0)} %`;
const formatRatio = (log2Ratio) => `×${(2 ** log2Ratio).toFixed(2)}`;

// The colour scale is symmetric in log2: a ratio of 2 and of 1/2 get the
// same strength of opposite colours; 1 (unchanged) is neutral.
function log2Values(ratios) {
  const values = new Float32Array(ratios.length);
  for (let i = 0; i < ratios.length; i++) values[i] = Math.log2(Math.max(ratios[i], 1e-30));
  return values;
}

// Outside the patch (NaN), and with no flattening, the surface stays neutral.
function compressionValues(pattern, vertexCount) {
  const values = new Float32Array(vertexCount);
  if (!pattern) return values;
  pattern.vertexError.forEach((error, vertex) => {
    if (Number.isFinite(error)) values[vertex] = error;
  });
  return values;
}
