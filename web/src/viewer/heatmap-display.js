// Keeps the heat map in step with what the view shows, when the Display panel
// turns it on: the core's distortion against the mesh as loaded (live
// previews included), or the compression error of the last flattening, on
// the same vertices the 2D pattern view colours by triangle.
//
// The distortion is the core's (Session.distortion in the worker: the area
// ratio, or the principal stretch farthest from 1); this file only maps it to
// colours, through log2, so that twice and half look equally strong. Edits
// bring the values along with their positions (editor.heatMapKind), so the
// map follows every live-preview frame without a second request; other
// changes (a load, undo, the panel) ask the worker.

// The compression error (|achieved / wanted - 1|) at full colour: 10 %, as
// in the pattern view.
export const COMPRESSION_ERROR_RANGE = 0.1;
// log2 of the ratio at full colour for the distortion maps: twice / half.
const DISTORTION_RANGE = 1.0;
const DISTORTION_KINDS = ['area', 'stretch'];

export class HeatmapDisplay {
  #latest = 0; // the newest refresh: older worker answers are dropped

  constructor({ editor, settings, meshView, reportError }) {
    this.editor = editor;
    this.settings = settings;
    this.meshView = meshView;
    this.reportError = reportError;
    settings.on('change', ({ section }) => section === 'display' && this.refresh());
    editor.on('mesh', () => this.refresh());
    editor.on('positions', ({ distortion }) => this.refresh(distortion));
    editor.on('pattern', () => this.refresh());
  }

  /** `distortion`: the core's values for the positions just shown, when an edit brought them. */
  refresh(distortion) {
    const kind = this.settings.values.display.heatMap;
    const document = this.editor.document;
    const refresh = ++this.#latest;
    this.editor.heatMapKind = DISTORTION_KINDS.includes(kind) ? kind : null;
    this.meshView.setHeatMapVisible(kind !== 'off');
    if (kind === 'off' || !document) return;
    if (kind === 'compression') {
      this.meshView.setHeatRange(COMPRESSION_ERROR_RANGE);
      this.meshView.showDistortion(compressionValues(this.editor.pattern, document.vertexCount));
      return;
    }
    this.meshView.setHeatRange(DISTORTION_RANGE);
    if (distortion) {
      this.meshView.showDistortion(log2Values(distortion));
      return;
    }
    this.editor.distortion(kind).then(
      (values) => {
        if (values && refresh === this.#latest) this.meshView.showDistortion(log2Values(values));
      },
      (error) => this.reportError(error, 'The heat map could not be computed'),
    );
  }
}

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
