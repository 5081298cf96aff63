// createModeller(container, options) -> {api, dispose}: one Anisoform
// modeller (solver worker, editor, viewer, interaction, tools, and with
// ui 'full' the side panel) living inside `container`. Everything it holds
// outside its own objects is registered in a Lifetime, so dispose() ends the
// pending frame, the ResizeObservers, the worker (and with it the WASM session)
// and every listener it added; several modellers on a page are independent.
import { createAnisoformApi } from '../api/create-api.js';
import { Editor } from '../editor/editor.js';
import { BrushCursor } from '../interaction/brush-cursor.js';
import { DragReadout } from '../interaction/drag-readout.js';
import { installKeyboardShortcuts } from '../interaction/keyboard-shortcuts.js';
import { installKeyboardZoom } from '../interaction/keyboard-zoom.js';
import { Picker } from '../interaction/picker.js';
import { PointerGestures } from '../interaction/pointer-gestures.js';
import { badParameter, supersededLoadError } from '../shared/errors.js';
import { Settings } from '../shared/settings.js';
import { createTools } from '../tools/tool-registry.js';
import { AxisGizmo } from '../viewer/axis-gizmo.js';
import { HeatmapDisplay } from '../viewer/heatmap-display.js';
import { DirectionDisplay } from '../viewer/direction-display.js';
import { GltfDisplay } from '../viewer/gltf-display.js';
import { MeshView } from '../viewer/mesh-view.js';
import { Viewer } from '../viewer/viewer.js';
import { SolverClient } from '../worker/solver-client.js';
import { SolverPool } from '../worker/solver-pool.js';
import { ViewAutosave } from '../document/view-autosave.js';
import { Request } from '../worker/protocol.js';
import { installFullUi } from './full-ui.js';
import { primeEditorListeners, scopedEmitter } from './ui-scope.js';
import { Lifetime } from './lifetime.js';
import { resolveDocumentSource, resolveMeshSource } from './mesh-source.js';
import { UI_MODES, buildLayout } from './modeller-layout.js';

const OPTIONS = ['ui', 'mesh', 'meshName', 'document', 'keyboard', 'autosave', 'workerUrl', 'wasmUrl', 'solvers', 'materials'];

/**
 * @param {HTMLElement} container
 * @param {object} [options]
 *   ui: 'full' | 'none' (default 'full'): the side panel, status bar and
 *       messages, or the 3D view alone (orbit only; edits through the api)
 *   mesh: URL string/URL, File, Blob, ArrayBuffer or typed array to load first (default: none)
 *   meshName: its file name when `mesh` is bytes (the extension picks the reader)
 *   document: an edit document (or its URL) to open with `mesh` as its base
 *             (api.open); if it cannot be opened, `mesh` is shown without
 *             it and the error is reported ('error'), `ready` resolving
 *   autosave: keep the work in IndexedDB and restore it on the next start
 *             instead of `mesh`, with its selection, tool settings and
 *             camera (document/view-autosave.js) (default false: one store per origin, so
 *             only a page with a single modeller should turn it on)
 *   keyboard: 'focus' (default: shortcuts while focus is inside the modeller) or 'page'
 *   workerUrl, wasmUrl: where the solver worker and its WASM are, when a
 *       bundler or server moved them from beside this module
 *   solvers: a pool (createSolverPool) to take a warm solver worker from,
 *       and to give it back to at dispose() (worker/solver-pool.js)
 *   materials: draw a mesh opened from glTF with its own materials,
 *       textures and vertex colours (default false: the editing surface,
 *       which shows the selection and heat maps); setMaterials() later
 */
export function createModeller(container, options = {}) {
  const { ui = 'full', mesh, meshName, document: editDocument, keyboard = 'focus', autosave = false, workerUrl, wasmUrl, solvers, materials = false } = checkOptions(container, options);

  const lifetime = new Lifetime();
  holding.add(container);
  lifetime.defer(() => holding.delete(container));
  const client = new SolverClient({ workerUrl, wasmUrl, pool: solvers });
  lifetime.defer(() => client.dispose());
  const editor = new Editor(client);
  // At dispose (before the worker ends): the page's and the embedder's listeners go, so a
  // call made after dispose (or one it cut off) rejects without an event.
  lifetime.defer(() => editor.clearListeners());
  // Milestones for the page's timing (app.spec): the first modeller's count.
  const starting = editor.start().then(() => performance.mark('anisoform:solver-ready'));

  // The layout of the ui shown, and what its parts hold (its panels'
  // listeners among them: ui-scope.js), until setUi lays the modeller out anew.
  let currentUi = ui;
  const layout = buildLayout(container, ui);
  let shownLayout = layout;
  let uiLifetime = layoutLifetime(layout);
  lifetime.defer(() => uiLifetime.dispose());
  const layoutNodes = new Set(layout.viewport.children);
  const settings = new Settings();
  settings.values.display.materials = materials;
  const viewer = new Viewer(layout.viewport, lifetime, solvers);
  viewer.on('contextlost', () => editor.report(Object.assign(new Error('The 3D view lost its WebGL context: the '
    + 'browser keeps about 16 a page and took this one (or its GPU was reset). The view comes back when the browser '
    + 'gives it again; dispose() modellers that are not shown.'), { code: 'display' })));
  viewer.on('contextrestored', () => editor.emit('notice', { message: 'The 3D view has its WebGL context again.', source: 'display' }));
  // The light drawing of a moving mesh on a CPU rasteriser is made in the
  // worker, once it has prepared the mesh or the mesh first moves: a select
  // right after a load waited for the simplification too (the 200k koala:
  // 1.4 s against 0.5 s).
  const meshView = new MeshView(viewer, {
    simplify: (triangles) => client.request(Request.simplify, { triangles }),
    startAfter: () => editor.whenPrepared(),
  });
  lifetime.defer(() => meshView.proxy.dispose());
  const gltfDisplay = new GltfDisplay(viewer, meshView);
  lifetime.defer(() => gltfDisplay.dispose());
  gltfDisplay.setWanted(materials);
  new AxisGizmo(viewer, lifetime);
  const picker = new Picker(viewer, meshView);
  viewer.setBoundsSource(() => editor.document?.bounds() ?? null);
  editor.attachView({ cameraState: () => viewer.cameraState(), pick: (x, y) => picker.pick(x, y) });

  // The normals and the picking BVH come from the worker (worker/mesh-display.js).
  editor.on('mesh', (loaded) => {
    meshView.setMesh(loaded.positions, loaded.triangles, loaded.display.normals);
    gltfDisplay.setSource(loaded.gltf, loaded.positions, loaded.triangles);
    picker.attach(loaded.display.bvh);
    viewer.frame({ defaultDirection: true, facing: loaded.facing() });
  });
  editor.on('positions', ({ positions, live }) => {
    meshView.showPositions(positions, { live });
    gltfDisplay.showPositions(positions, { live });
    picker.markStale();
  });
  editor.on('selection', ({ weights }) => meshView.showSelection(weights));
  settings.on('change', ({ section }) => {
    if (section !== 'display') return;
    const display = settings.values.display;
    meshView.setSelectionVisible(display.selection);
    meshView.setFlatShading(display.flatShading);
    meshView.setWireframe(display.wireframe);
    gltfDisplay.setWanted(display.materials);
  });

  // Errors the editor has reported already are not shown twice.
  const reportError = (error, context) => editor.report(error, context);
  const directionDisplay = new DirectionDisplay({ editor, settings, viewer, meshView, lifetime });
  const heatmapDisplay = new HeatmapDisplay({ editor, settings, meshView, viewport: layout.viewport, lifetime, reportError, fileLook: () => gltfDisplay.active });
  const tools = createTools({
    editor,
    viewer,
    settings,
    picker,
    brushCursor: new BrushCursor(viewer),
    dragReadout: new DragReadout(viewer),
    reportError,
    arrowPreview: (arrows) => directionDisplay.showArrows(arrows),
  });
  // Without the panel there is no way to pick a tool: the pointer orbits only.
  const activeTool = () => (currentUi === 'full' ? tools.get(settings.values.tool) ?? null : null);
  const gestures = new PointerGestures(viewer, picker, activeTool, lifetime);
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

  // Ready means drawn: wait for the frame that shows the mesh (a big one's
  // buffers reach the GPU over a few frames first: viewer/staged-upload.js).
  async function drawn() {
    performance.mark('anisoform:mesh-loaded');
    await meshView.shown;
    await new Promise((resolve) => {
      const off = viewer.on('frame', () => {
        off();
        resolve();
      });
      viewer.requestRender();
    });
    performance.mark('anisoform:interactive');
  }

  // Meshes asked for (the starting one, load(), open() with a mesh), counted
  // when asked: one whose download ends after a later one was asked for is
  // not loaded (the starting mesh, downloaded last, replaced the product
  // page's own load while both promises said the page's mesh was in).
  let meshRequests = 0;
  // The mesh download overlaps with compiling the WASM in the worker.
  const startingRequest = mesh === undefined ? 0 : ++meshRequests;
  const loadsBeforeStart = editor.loadsAsked;
  const meshSource = mesh === undefined ? null : resolveMeshSource(mesh, meshName);
  meshSource?.catch(() => {}); // reported through `ready`
  const documentSource = editDocument === undefined ? undefined : resolveDocumentSource(editDocument);
  documentSource?.catch(() => {}); // reported below, with the mesh shown without it
  // The selection, tool, settings and camera kept beside the autosaved work (autosave only).
  const viewAutosave = autosave ? new ViewAutosave({ editor, settings, viewer, lifetime }) : null;
  const ready = (async () => {
    const [, source] = await Promise.all([starting, meshSource]);
    if (autosave && !lifetime.disposed) {
      editor.ops.enableAutosave();
      lifetime.defer(() => editor.ops.disableAutosave());
    }
    const restored = autosave && editDocument === undefined ? await editor.ops.restoreAutosave() : null;
    if (restored) {
      viewAutosave.apply(restored);
      await drawn();
      return;
    }
    if (!source) {
      if (editDocument !== undefined) throw openWithoutMesh();
      return;
    }
    // A load() or open() asked for since (api.load too): its mesh is shown.
    if (startingRequest !== meshRequests || editor.loadsAsked !== loadsBeforeStart) return;
    if (editDocument === undefined) {
      await editor.load(source.data, source.name);
    } else {
      if (typeof api.open !== 'function') throw badParameter('createModeller: this build cannot open edit documents (no api.open)');
      try {
        await api.open(await documentSource, source.data, source.name);
      } catch (error) {
        // Edits that cannot be opened (not found, not JSON, made on another
        // mesh, an op the core refuses) leave the mesh shown without them,
        // the error reported: a product page still shows its product.
        if (!editor.document) await editor.load(source.data, source.name);
        reportError(error, 'The edits were not opened; the mesh is shown without them');
      }
    }
    await drawn();
  })();
  ready.catch((error) => {
    if (!lifetime.disposed) reportError(error, 'The modeller could not start');
  });
  // The view is saved from when the page shows its work: the states a
  // restore passes through are not.
  if (viewAutosave) ready.finally(() => viewAutosave.start()).catch(() => {});

  const api = createAnisoformApi({ editor, viewer, picker, ready });

  // Arrow keys pan and Shift+arrows orbit while the 3D view has the focus
  // (about 9° a press on a 400 px high view).
  viewer.controls.listenToKeyEvents(viewer.canvas);
  viewer.controls.keyRotateSpeed = 10;
  installKeyboardZoom(viewer, lifetime);
  // What is drawn over the view (the axis gizmo, the brush cursor, the heat
  // map's legend) moves with it to a new layout.
  const overlays = [...layout.viewport.children].filter((node) => node !== viewer.canvas && !layoutNodes.has(node));

  // The parts of a layout: its keys, and with ui 'full' the panels.
  function installUi(shown, shownUi, held, { prime = false } = {}) {
    const keyTarget = keyboard === 'page' ? window : shown.root;
    installKeyboardShortcuts(keyTarget, held, {
      undo: () => api.undo(),
      redo: () => api.redo(),
      cancel: () => gestures.cancel() || editor.cancelGesture() || editor.cancelSolve() || editor.ops.dropPreview(),
      frame: () => api.frame(),
    });
    // The panel's own form events stay inside: outside, 'change' is the api's
    // (the <anisoform-modeller> element relays it under that name).
    held.listen(shown.root, 'change', (event) => event.stopPropagation());
    if (shownUi !== 'full') return;
    const heard = [];
    installFullUi(shown, {
      api, editor: scopedEmitter(editor, held, heard), settings: scopedEmitter(settings, held, heard),
      tools, viewer, picker, reportError, lifetime: held, keyTarget,
    });
    if (prime) primeEditorListeners(heard, editor);
  }
  installUi(layout, ui, uiLifetime);

  /**
   * Lays the same modeller out for another ui ('full' or 'none'): its worker,
   * mesh, document, selection, camera and an edit in flight go on; only the
   * panels change (the element's ui attribute).
   */
  function setUi(next) {
    if (!UI_MODES.includes(next)) throw badParameter(`setUi: ui must be ${UI_MODES.map((m) => `'${m}'`).join(' or ')}, got '${next}'`);
    if (next === currentUi || lifetime.disposed) return;
    gestures.cancel(); // a stroke of the panel's tool ends with the panel
    // The focus stays in the modeller: on the same control in the new
    // layout, else on the 3D view (it fell to the page's body, and with
    // keyboard 'focus' the shortcuts stopped reaching the modeller).
    const focused = shownLayout.root.contains(document.activeElement) ? document.activeElement : null;
    const nextLayout = buildLayout(container, next);
    viewer.moveTo(nextLayout.viewport, overlays);
    heatmapDisplay.legend.moveTo(nextLayout.viewport);
    const previous = uiLifetime;
    currentUi = next;
    shownLayout = nextLayout;
    uiLifetime = layoutLifetime(nextLayout);
    previous.dispose();
    installUi(nextLayout, next, uiLifetime, { prime: true });
    if (focused) focusLike(focused, nextLayout.root, viewer.canvas);
  }

  /** Loads a URL as well as what api.load takes; failures are reported as 'error' events too. */
  async function load(source, name) {
    const request = ++meshRequests;
    let resolved;
    try {
      resolved = await resolveMeshSource(source, name);
    } catch (error) {
      throw reportError(error, 'Could not load the mesh');
    }
    if (request !== meshRequests) throw supersededLoadError();
    return api.load(resolved.data, resolved.name);
  }

  /**
   * Opens an edit document (or its URL) on the mesh loaded, or on `mesh`
   * (as load takes it) as its base; failures are reported as 'error' events too.
   */
  async function open(documentSource, mesh, name) {
    const request = mesh === undefined ? null : ++meshRequests;
    let json;
    let resolved;
    // A mesh that cannot be fetched is said as such ('meshFailed'): it used
    // to be "Could not open the edits", and the element fetched it again.
    const meshPart = mesh === undefined ? undefined : resolveMeshSource(mesh, name).catch((error) => {
      throw Object.assign(reportError(error, 'Could not load the mesh'), { meshFailed: true });
    });
    try {
      [json, resolved] = await Promise.all([resolveDocumentSource(documentSource), meshPart]);
    } catch (error) {
      if (error.meshFailed) throw error;
      throw reportError(error, 'Could not open the edits');
    }
    if (request !== null && request !== meshRequests) throw supersededLoadError();
    return resolved ? api.open(json, resolved.data, resolved.name) : api.open(json);
  }

  const modeller = Object.freeze({
    api,
    load,
    open,
    /** Draws a glTF mesh with its own materials (true) or the editing surface (false). */
    setMaterials: (on) => {
      if (typeof on !== 'boolean') throw badParameter(`setMaterials: expected true or false, got ${JSON.stringify(on)}`);
      settings.update('display', { materials: on });
    },
    setUi,
    /** Stops everything this modeller started; the container is left as it was. */
    dispose: () => lifetime.dispose(),
    /** Listeners and clean-up steps still held (0 after dispose): for tests. */
    get held() {
      return lifetime.size;
    },
  });
  return modeller;
}

// What one layout holds, its DOM first (removed when the layout is left).
function layoutLifetime(layout) {
  const held = new Lifetime();
  held.defer(() => layout.element.remove());
  return held;
}

// The containers that hold a live modeller: a second one in the same
// container stacked its view under the first's and overflowed it.
const holding = new WeakSet();

function checkOptions(container, options) {
  if (!(container instanceof HTMLElement)) throw badParameter('createModeller: container must be an HTML element');
  if (holding.has(container)) throw badParameter('createModeller: this container holds a modeller already: dispose() it first, or give each modeller its own container');
  if (options === null || typeof options !== 'object') throw badParameter('createModeller: options must be an object');
  for (const key of Object.keys(options)) {
    if (!OPTIONS.includes(key)) throw badParameter(`createModeller: unknown option '${key}' (options: ${OPTIONS.join(', ')})`);
  }
  if (options.ui !== undefined && !UI_MODES.includes(options.ui)) {
    throw badParameter(`createModeller: ui must be ${UI_MODES.map((m) => `'${m}'`).join(' or ')}, got '${options.ui}'`);
  }
  if (options.autosave !== undefined && typeof options.autosave !== 'boolean') {
    throw badParameter(`createModeller: autosave must be true or false, got ${JSON.stringify(options.autosave)}`);
  }
  if (options.solvers !== undefined && !(options.solvers instanceof SolverPool)) {
    throw badParameter('createModeller: solvers must be a pool made by createSolverPool()');
  }
  if (options.materials !== undefined && typeof options.materials !== 'boolean') {
    throw badParameter(`createModeller: materials must be true or false, got ${JSON.stringify(options.materials)}`);
  }
  if (options.keyboard !== undefined && !['focus', 'page'].includes(options.keyboard)) {
    throw badParameter(`createModeller: keyboard must be 'focus' or 'page', got '${options.keyboard}'`);
  }
  return options;
}

function openWithoutMesh() {
  return badParameter('createModeller: the document option needs its base mesh in the mesh option');
}

// Focuses the control of `root` that is `control`'s counterpart (its test
// id: a banner's button is in both layouts), or `fallback`.
function focusLike(control, root, fallback) {
  const testId = control.dataset?.testid;
  const counterpart = testId && root.querySelector(`[data-testid="${CSS.escape(testId)}"]`);
  (counterpart || fallback).focus();
}
