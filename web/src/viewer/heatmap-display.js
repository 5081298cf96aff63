// Keeps the heat map in step with what the view shows, when the Display panel
// turns it on: a distortion against the mesh as loaded (live previews
// included), or the compression error of the last flattening, on the same
// vertices the 2D pattern view colours by triangle.
import { computeDistortion } from './distortion.js';

// The compression error (|achieved / wanted - 1|) at full colour: 10 %, as
// in the pattern view.
export const COMPRESSION_ERROR_RANGE = 0.1;
// log2 ratio at full colour for the distortion maps: twice / half.
const DISTORTION_RANGE = 1.0;

export class HeatmapDisplay {
  constructor({ editor, settings, meshView }) {
    this.editor = editor;
    this.settings = settings;
    this.meshView = meshView;
    settings.on('change', ({ section }) => section === 'display' && this.refresh());
    editor.on('mesh', () => this.refresh());
    editor.on('positions', ({ positions }) => this.refresh(positions));
    editor.on('pattern', () => this.refresh());
  }

  refresh(positions = this.meshView.displayedPositions) {
    const kind = this.settings.values.display.heatMap;
    const document = this.editor.document;
    this.meshView.setHeatMapVisible(kind !== 'off');
    if (kind === 'off' || !document) return;
    if (kind === 'compression') {
      this.meshView.setHeatRange(COMPRESSION_ERROR_RANGE);
      this.meshView.showDistortion(compressionValues(this.editor.pattern, document.vertexCount));
      return;
    }
    this.meshView.setHeatRange(DISTORTION_RANGE);
    this.meshView.showDistortion(computeDistortion(kind, document.loadedPositions, positions, document.triangles));
  }
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
