// The public API object (issue 3 §3), exposed as window.anisoform. The side
// panel drives the editor through this same object wherever it offers the
// operation (load, select, undo, redo, reset, export, flatten, exportPattern,
// frame);
// tests and embedders use nothing else. Declarations: anisoform.d.ts beside
// this file.
import { badParameter } from '../shared/errors.js';

const EVENTS = ['change', 'error', 'progress', 'positions', 'document'];

// The calls that ask the solver for work.
const AFTER_DISPOSE_REFUSED = ['load', 'select', 'deform', 'open', 'setParameter', 'setOpEnabled', 'removeOp', 'moveOp',
  'setRegion', 'renameOp', 'export', 'flatten', 'exportPattern'];

// The events whose payload is the page's own state (the positions shown, the
// edit document): a listener gets a copy, as positions() and document()
// give, so that changing it changes nothing of the modeller's. The arrays
// are copied when first read: a listener that only counts frames (live)
// costs a preview frame no copy of its positions.
const PAYLOAD_COPIES = {
  positions: ({ positions, live, distortion }) => {
    const event = { live };
    copiedOnRead(event, 'positions', positions);
    if (distortion) copiedOnRead(event, 'distortion', distortion);
    return event;
  },
  document: (document) => document?.toJSON() ?? null,
};

function copiedOnRead(target, key, array) {
  let copy = null;
  Object.defineProperty(target, key, { enumerable: true, get: () => (copy ??= array.slice()) });
}

export function createAnisoformApi({ editor, viewer, picker, ready }) {
  const document = () => {
    if (!editor.document) throw badParameter('no mesh is loaded yet: await anisoform.ready');
    return editor.document;
  };

  // Errors reach the user (the banner) and the caller (a rejected promise with the code).
  const reported = (promise, context) => promise.catch((error) => {
    throw editor.report(error, context);
  });

  const api = {
    version: '0.1.0',
    ready,

    load: (source, name) => editor.load(source, name),

    info() {
      const { info } = document();
      return {
        vertices: info.vertices,
        triangles: info.triangles,
        components: info.components,
        boundaryLoops: info.boundaryLoops,
        unitGuess: { ...info.unitGuess },
      };
    },

    positions: () => document().positions.slice(),

    // The core's selection rule, run in the solver worker: a promise.
    // A refusal, no mesh loaded included, is reported ('error') as every other.
    select: (region, options = {}) => reported(Promise.resolve().then(() => {
      document();
      return editor.select(region, options);
    })),

    selection: () => document().selection.slice(),

    deform: (op) => editor.deform(op),

    // The edit document (document/op-stack.js): the page's source of truth.
    document: () => editor.ops.toJSON(),
    open: (json, meshBytes, meshName) =>
      reported(editor.ops.open(json, meshBytes, meshName), 'The document was not opened'),
    setParameter: (opId, patch, options) =>
      reported(editor.ops.setParameter(opId, patch, options), 'The parameter was not applied'),
    setOpEnabled: (opId, enabled) => reported(editor.ops.setEnabled(opId, enabled), 'The op was not changed'),
    removeOp: (opId) => reported(editor.ops.removeOp(opId), 'The op was not deleted'),
    moveOp: (opId, index) => reported(editor.ops.moveOp(opId, index), 'The op was not moved'),
    renameOp: (opId, name) => reported(editor.ops.renameOp(opId, name), 'The op was not renamed'),
    setRegion: (opId, steps) => reported(editor.ops.setRegion(opId, steps), 'The region was not changed'),

    cancel: () => editor.cancelSolve() || editor.ops.dropPreview(),
    undo: () => editor.undo(),
    redo: () => editor.redo(),
    reset: () => editor.reset(),

    export: (format) => editor.export(format),

    // A garment pattern of the mesh (or its selection) with the wanted
    // compression built in; the mesh and its history are untouched.
    flatten: (options = {}) => reported(Promise.resolve().then(async () => {
      document();
      const result = await editor.flatten(options);
      return {
        uv: result.uv.slice(),
        metrics: { ...result.metrics },
        triangles: result.triangles.slice(),
        compressionError: result.compressionError.slice(),
        crossError: result.crossError.slice(),
        grainlines: result.grainlines.map((g) => [...g]),
      };
    })),

    exportPattern: (format, options) => editor.exportPattern(format, options),

    on(event, callback) {
      if (!EVENTS.includes(event)) {
        throw badParameter(`unknown event '${event}': use ${EVENTS.join(', ')}`);
      }
      if (typeof callback !== 'function') {
        throw badParameter('on() needs a callback function');
      }
      return editor.on(event, PAYLOAD_COPIES[event] ? (payload) => callback(PAYLOAD_COPIES[event](payload)) : callback);
    },

    pick([x, y]) {
      document();
      return picker.pick(x, y);
    },

    // Fits the camera to the whole mesh, keeping the view direction (the Frame button, F, Home).
    frame: () => viewer.frame(),

    camera() {
      return {
        ...viewer.cameraState(),
        position: viewer.camera.position.toArray(),
        target: viewer.controls.target.toArray(),
      };
    },
  };
  // Called after the modeller's dispose(): refused as such (work asked for
  // before it rejects as 'cancelled', solver-client.js).
  for (const name of AFTER_DISPOSE_REFUSED) {
    const call = api[name];
    api[name] = (...args) => (editor.disposed
      ? Promise.reject(badParameter(`${name}(): this modeller was disposed`))
      : call(...args));
  }
  return Object.freeze(api);
}
