// Wires the page together: solver worker, editor, viewer, interaction, tools,
// panels and the public API (window.anisoform), then loads the default mesh.
import { createAnisoformApi } from './api/create-api.js';
import { opsPanel } from './document/ops-panel.js';
import { Editor } from './editor/editor.js';
import { Settings } from './shared/settings.js';
import { BrushCursor } from './interaction/brush-cursor.js';
import { installKeyboardShortcuts } from './interaction/keyboard-shortcuts.js';
import { Picker } from './interaction/picker.js';
import { PointerGestures } from './interaction/pointer-gestures.js';
import { createTools } from './tools/tool-registry.js';
import { directionPanel } from './ui/direction-panel.js';
import { displayPanel } from './ui/display-panel.js';
import { installDropZone } from './ui/drop-zone.js';
import { filePanel } from './ui/file-panel.js';
import { flattenPanel } from './ui/flatten-panel.js';
import { frameButton } from './ui/frame-button.js';
import { showWhen } from './ui/fields.js';
import { historyButtons } from './ui/history-panel.js';
import { installMessages } from './ui/messages.js';
import { methodPanel } from './ui/method-panel.js';
import { modeSwitch } from './ui/mode-switch.js';
import { patternPane } from './ui/pattern-pane.js';
import { selectionPanel } from './ui/selection-panel.js';
import { statusBar } from './ui/status-bar.js';
import { toolPanel } from './ui/tool-panel.js';
import { DirectionDisplay } from './viewer/direction-display.js';
import { HeatmapDisplay } from './viewer/heatmap-display.js';
import { MeshView } from './viewer/mesh-view.js';
import { Viewer } from './viewer/viewer.js';
import { SolverClient } from './worker/solver-client.js';

// Public domain "Spot" by Keenan Crane (see spot_README.txt beside it).
const DEFAULT_MESH = 'spot_triangulated.obj';

// The worker and the default mesh's download start first: compiling the
// WASM and fetching overlap with building the page.
const client = new SolverClient();
const editor = new Editor(client);
const starting = editor.start().then(() => performance.mark('anisoform:solver-ready'));
const defaultMeshBytes = fetch(new URL(DEFAULT_MESH, document.baseURI)).then((response) => {
  if (!response.ok) throw new Error(`The default mesh could not be fetched (HTTP ${response.status})`);
  return response.arrayBuffer();
});

const settings = new Settings();
const viewer = new Viewer(document.getElementById('viewport'));
const meshView = new MeshView(viewer);
const picker = new Picker(viewer, meshView);
viewer.setBoundsSource(() => editor.document?.bounds() ?? null);
editor.attachView({ cameraState: () => viewer.cameraState(), pick: (x, y) => picker.pick(x, y) });

editor.on('mesh', (mesh) => {
  meshView.setMesh(mesh.positions, mesh.triangles);
  editor.emit('progress', { stage: 'parse', message: 'Building the picking structure' });
  picker.rebuild();
  viewer.frame({ defaultDirection: true });
});
editor.on('positions', ({ positions }) => {
  meshView.showPositions(positions);
  picker.markStale();
});
editor.on('selection', ({ weights }) => meshView.showSelection(weights));
settings.on('change', ({ section }) => {
  if (section === 'display') meshView.setSelectionVisible(settings.values.display.selection);
});

// Errors the editor has reported already are not shown twice.
const reportError = (error, context) => editor.report(error, context);
const brushCursor = new BrushCursor(viewer);
const directionDisplay = new DirectionDisplay({ editor, settings, viewer, meshView });
new HeatmapDisplay({ editor, settings, meshView, reportError });
const tools = createTools({
  editor,
  viewer,
  settings,
  picker,
  brushCursor,
  reportError,
  arrowPreview: (arrows) => directionDisplay.showArrows(arrows),
});
const gestures = new PointerGestures(viewer, picker, () => tools.get(settings.values.tool) ?? null);
// Arrows, the last screen drag and a stroke in progress belong to the mesh
// they were made on; a load drops them before the new mesh is shown.
editor.bindToMesh(() => {
  gestures.cancel();
  settings.resetMeshBound();
});
let previousTool = settings.values.tool;
settings.on('change', ({ section }) => {
  if (section !== 'tool') return;
  gestures.cancel();
  tools.get(previousTool)?.deactivate?.();
  previousTool = settings.values.tool;
});

const ready = (async () => {
  const [, bytes] = await Promise.all([starting, defaultMeshBytes]);
  // The autosaved work (document/autosave.js), else the default mesh.
  if (!(await editor.ops.restoreAutosave())) await editor.load(bytes, DEFAULT_MESH);
  performance.mark('anisoform:mesh-loaded');
  // Ready means drawn: wait for the frame that shows the mesh.
  await new Promise((resolve) => {
    const off = viewer.on('frame', () => {
      off();
      resolve();
    });
    viewer.requestRender();
  });
  performance.mark('anisoform:interactive');
})();
ready.catch((error) => reportError(error, 'The page could not start'));

const api = createAnisoformApi({ editor, viewer, picker, ready });
window.anisoform = api;

const panel = document.getElementById('side-panel');
const inMode = (mode, element) => showWhen(settings, 'mode', element, (current) => current === mode);
panel.append(
  modeSwitch({ settings, app: document.getElementById('app') }),
  filePanel({ api, editor, reportError }),
  historyButtons({ api, editor }),
  opsPanel({ api, editor }),
  toolPanel({ settings, tools, reportError }),
  selectionPanel({ api, editor }),
  inMode('deform', directionPanel({ settings })),
  inMode('deform', methodPanel({ settings })),
  inMode('flatten', flattenPanel({ api, editor, settings, reportError })),
  displayPanel({ settings }),
);
patternPane(document.getElementById('pattern-pane'), { editor, settings });
statusBar(document.getElementById('status-bar'), { editor, viewer });
installMessages(document.getElementById('viewport'), { editor });
installDropZone(document.getElementById('drop-overlay'), { api, reportError });
installKeyboardShortcuts({
  undo: () => api.undo(),
  redo: () => api.redo(),
  cancel: () => gestures.cancel() || editor.cancelGesture(),
  frame: () => api.frame(),
});
frameButton(document.getElementById('viewport'), { api });
