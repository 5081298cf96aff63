// Keeps the distortion heat map in step with the displayed positions (live
// previews included) when the Display panel turns it on.
import { computeDistortion } from './distortion.js';

export class HeatmapDisplay {
  constructor({ editor, settings, meshView }) {
    this.editor = editor;
    this.settings = settings;
    this.meshView = meshView;
    settings.on('change', ({ section }) => section === 'display' && this.refresh());
    editor.on('mesh', () => this.refresh());
    editor.on('positions', ({ positions }) => this.refresh(positions));
  }

  refresh(positions = this.meshView.displayedPositions) {
    const kind = this.settings.values.display.heatMap;
    const document = this.editor.document;
    this.meshView.setHeatMapVisible(kind !== 'off');
    if (kind === 'off' || !document) return;
    this.meshView.showDistortion(computeDistortion(kind, document.loadedPositions, positions, document.triangles));
  }
}
