// The editor: the page's model of an editing session, between the UI/API and
// the solver worker. It owns the mesh document, the history and the live
// gesture, and announces changes as events:
//   'mesh'       a new mesh was loaded (payload: MeshDocument)
//   'positions'  {positions, live}: committed positions, or a live preview
//   'selection'  {weights, count, live}: committed weights, or a brush stroke in progress
//   'history'    {canUndo, canRedo, undoLabel, redoLabel}
//   'stats'      {ms, iterations, live, factorizations}
//   'progress'   {stage, message, fraction?}; stage 'done' ends it
//   'busy'       boolean: a committed edit is being solved
//   'error'      {code, message}: every refusal and failure, in plain words
//                that say what to do (report() is the one way in)
//   'loading'    {name}: a load started; old messages no longer apply
//   'notice'     {message, details}: what a load repaired or found (plain
//                words; details: the full list, one sentence each)
//   'warning'    {message}: a committed edit folded triangles over
//   'pattern'    the last flattening (FlattenPayload plus its options), or null
//                when the mesh, its positions or the flattened selection changed
//   'change'     {reason}: anything committed changed (load, edit, selection, undo)
import { PositionsCommand } from '../commands/positions-command.js';
import { History } from '../commands/history.js';
import { SelectionCommand } from '../commands/selection-command.js';
import { importGltf } from '../io/import-gltf.js';
import { exportMesh } from '../io/export-mesh.js';
import { readerFor } from '../io/mesh-formats.js';
import { readFileBytes } from '../io/read-file.js';
import { applyFalloff, combineWeights, countSelected, regionWeights } from '../selection/region-weights.js';
import { Request } from '../worker/protocol.js';
import { EventEmitter } from './event-emitter.js';
import { MeshDocument } from './mesh-document.js';
import { describeProblems } from './problem-summary.js';
import { toSolverOp } from './solver-op.js';

export class Editor extends EventEmitter {
  /** @type {MeshDocument|null} */
  document = null;
  /** The last flattening of the committed mesh (see flatten()), or null. */
  pattern = null;
  history = new History();
  #client;
  #view = null;
  #selectionSent = null;
  #gesture = null;
  #committing = 0;
  #gestureCount = 0;
  #meshBound = [];
  #reported = new WeakSet();

  constructor(client) {
    super();
    this.#client = client;
    client.on('progress', (progress) => this.emit('progress', progress));
    this.history.on('change', (state) => this.emit('history', state));
  }

  /** The viewer's camera and picking, needed for screen-space directions. */
  attachView(view) {
    this.#view = view;
  }

  async start() {
    await this.#client.request(Request.init);
  }

  get busy() {
    return this.#committing > 0;
  }

  get gestureActive() {
    return this.#gesture !== null;
  }

  // ---- loading -------------------------------------------------------------

  /**
   * Registers state that belongs to the loaded mesh outside the editor (the
   * arrows, the last screen drag, a tool's stroke): `reset` runs at every
   * load, before the new mesh is announced, so nothing of the old mesh ever
   * meets the new one.
   */
  bindToMesh(reset) {
    this.#meshBound.push(reset);
  }

  /** Loads a File, Blob or ArrayBuffer; on failure the current mesh stays. */
  async load(source, name) {
    try {
      if (typeof name !== 'string' || !name) {
        name = source?.name ?? '';
        if (!name) throw Object.assign(new Error('load() needs a file name with its extension, e.g. "part.stl"'), { code: 'bad-parameter' });
      }
      this.emit('loading', { name });
      const reader = readerFor(name);
      const bytes = await this.#bytesOf(source, name);
      this.emit('progress', { stage: 'parse', message: `Reading ${name}` });
      let payload;
      if (reader === 'core') {
        payload = await this.#client.request(Request.loadFile, { bytes, name }, [bytes]);
      } else {
        const { positions, triangles, notes } = await importGltf(bytes, name);
        // glTF splits vertices at seams; welding exact duplicates joins the surface.
        payload = await this.#client.request(Request.setMesh, { positions, triangles, weld: true }, [
          positions.buffer,
          triangles.buffer,
        ]);
        payload.info.notes = [...notes, ...(payload.info.notes ?? [])];
      }
      this.#adopt(payload, name);
      return { vertices: payload.info.vertices, triangles: payload.info.triangles };
    } catch (error) {
      this.emit('progress', { stage: 'done', message: '' });
      throw this.#reportError(loadError(error, name, this.document), `Could not load ${name || 'the file'}`);
    }
  }

  async #bytesOf(source, name) {
    if (source instanceof ArrayBuffer) return source.slice(0); // the caller keeps theirs
    if (ArrayBuffer.isView(source)) return source.buffer.slice(source.byteOffset, source.byteOffset + source.byteLength);
    if (source instanceof Blob) {
      this.emit('progress', { stage: 'read', message: `Reading ${name}`, fraction: 0 });
      return readFileBytes(source, (fraction) =>
        this.emit('progress', { stage: 'read', message: `Reading ${name}`, fraction }),
      );
    }
    throw Object.assign(new Error('load() takes a File, Blob or ArrayBuffer'), { code: 'bad-parameter' });
  }

  // The one place where a new mesh replaces the old one: everything tied to
  // the old mesh's vertices (the live edit, the pattern and its heat map, the
  // selection, the history, the arrows and whatever else bindToMesh named)
  // is dropped before the new mesh is announced.
  #adopt({ info, positions, triangles }, name) {
    this.#abandonGesture();
    this.#dropPattern();
    for (const reset of this.#meshBound) reset();
    this.document = new MeshDocument({ name, positions, triangles, info });
    this.#selectionSent = null;
    this.history.clear();
    this.emit('mesh', this.document);
    const notice = describeProblems(info);
    if (notice) this.emit('notice', notice);
    this.emit('change', { reason: 'load' });
    this.#prepareSolver();
  }

  // Factorizes in the background; the page stays usable, and the first edit
  // queues behind this in the worker instead of paying for it mid-drag.
  #prepareSolver() {
    const document = this.document;
    this.#selectionSent = null; // prepare leaves an empty selection in the session
    this.#client
      .request(Request.prepare)
      .then(() => {
        if (this.document === document) this.emit('progress', { stage: 'done', message: 'Ready' });
      })
      .catch((error) => {
        if (this.document === document) this.#reportError(error, 'The solver could not prepare this mesh');
      });
  }

  // ---- selection -----------------------------------------------------------

  select(region, options = {}) {
    const document = this.#requireDocument();
    let weights = regionWeights(document.positions, region);
    const falloff = options.falloff ?? 0;
    if (falloff !== 0) applyFalloff(weights, document.adjacency, document.positions, falloff);
    weights = combineWeights(document.selection, weights, options.mode ?? 'replace');
    return this.setSelection(weights, 'Select');
  }

  /** Commits new weights as one undoable step; returns the selected count. */
  setSelection(weights, label) {
    const document = this.#requireDocument();
    const before = document.selection;
    this.#applySelection(weights);
    this.history.push(new SelectionCommand(label, before, weights, (w) => this.#applySelection(w)));
    return document.selectionCount;
  }

  /** Shows weights of a stroke in progress without committing them. */
  showSelection(weights) {
    this.emit('selection', { weights, count: null, live: true });
  }

  #applySelection(weights) {
    const document = this.#requireDocument();
    if (this.pattern?.options.patch === 'selection') this.#dropPattern();
    document.setSelection(weights, countSelected(weights));
    this.emit('selection', { weights, count: document.selectionCount, live: false });
    this.emit('change', { reason: 'selection' });
  }

  // An empty selection means "the whole mesh": a first drag on a freshly
  // loaded mesh does something visible instead of nothing.
  #syncSelection() {
    const document = this.#requireDocument();
    const key = document.selectionCount === 0 ? 'whole' : document.selectionVersion;
    if (key === this.#selectionSent) return;
    const weights =
      document.selectionCount === 0 ? new Float32Array(document.vertexCount).fill(1) : document.selection.slice();
    this.#selectionSent = key;
    // Requests are ordered, so the deform that follows sees these weights.
    this.#client.request(Request.setSelection, { weights }, [weights.buffer]).catch((error) => {
      this.#selectionSent = null;
      this.#reportError(error, 'The selection could not be sent to the solver');
    });
  }

  // ---- deformation ---------------------------------------------------------

  /** One committed, undoable edit; a refusal is reported like a failure. */
  async deform(op, label) {
    let solverOp;
    let document;
    try {
      document = this.#requireDocument();
      label ??= describeEdit(op);
      if (this.#gesture) throw Object.assign(new Error('an interactive edit is in progress: finish the drag first'), { code: 'bad-parameter' });
      solverOp = toSolverOp(op, document, this.#view);
    } catch (error) {
      throw this.report(error, `${label ?? 'The edit'} was not applied`);
    }
    return this.#commit(document, solverOp, label);
  }

  async #commit(document, solverOp, label) {
    this.#syncSelection();
    this.#committing++;
    this.emit('busy', true);
    try {
      const before = document.positions;
      const { positions, stats } = await this.#client.request(Request.deform, { op: solverOp, commit: true });
      if (this.document !== document) return stats; // a new mesh arrived meanwhile
      this.#applyPositions(positions);
      this.history.push(new PositionsCommand(label, before, positions, (p) => this.#restorePositions(p)));
      this.emit('stats', { ...stats, live: false });
      if (stats.inverted > 0) this.emit('warning', { message: foldOverWarning(stats.inverted) });
      return { iterations: stats.iterations, energy: stats.energy, ms: stats.ms, inverted: stats.inverted };
    } catch (error) {
      throw this.#reportError(error, `${label} failed`);
    } finally {
      this.#committing--;
      this.emit('busy', this.#committing > 0);
    }
  }

  /** Starts a live edit (a drag). Returns false while another edit runs. */
  beginGesture() {
    if (!this.document || this.#gesture || this.#committing) return false;
    this.#gesture = { id: ++this.#gestureCount, lastOp: null };
    this.#syncSelection();
    this.emit('gesture', true);
    return true;
  }

  /** Shows the edit `op` live; stale results are dropped. */
  updateGesture(op) {
    const gesture = this.#gesture;
    if (!gesture) return;
    const solverOp = toSolverOp(op, this.document, this.#view);
    gesture.lastOp = solverOp;
    this.#client
      .preview(solverOp)
      .then((result) => {
        if (!result || this.#gesture !== gesture) return;
        this.emit('positions', { positions: result.positions, live: true });
        this.emit('stats', { ...result.stats, live: true });
      })
      .catch((error) => {
        if (this.#gesture === gesture) this.#reportError(error, 'The live preview failed');
      });
  }

  /** Ends the live edit and commits its last state (fully solved) as one step. */
  async commitGesture(label) {
    const gesture = this.#gesture;
    if (!gesture) return null;
    this.#gesture = null;
    this.#client.dropQueuedPreview();
    this.emit('gesture', false);
    if (!gesture.lastOp) {
      await this.#client.request(Request.cancel).catch((error) => {
        throw this.#reportError(error, 'Cancel failed');
      });
      return null;
    }
    const { preview, ...finalOp } = gesture.lastOp;
    return this.#commit(this.document, finalOp, label);
  }

  /** Esc: drops the live edit; the mesh returns to its committed state. */
  cancelGesture() {
    if (!this.#gesture) return false;
    this.#abandonGesture();
    this.#client.request(Request.cancel).catch((error) => this.#reportError(error, 'Cancel failed'));
    this.emit('positions', { positions: this.document.positions, live: false });
    return true;
  }

  #abandonGesture() {
    if (!this.#gesture) return;
    this.#gesture = null;
    this.#client.dropQueuedPreview();
    this.emit('gesture', false);
  }

  /** Per-vertex unit directions of a direction source, for the glyphs. */
  async directionField(direction) {
    const document = this.#requireDocument();
    const solverOp = toSolverOp({ method: 'anarap', direction, transform: {} }, document, this.#view);
    const { field } = await this.#client.request(Request.directionField, { direction: solverOp.direction });
    return this.document === document ? field : null;
  }

  // ---- history -------------------------------------------------------------

  undo() {
    if (this.#gesture || this.#committing) return false;
    return this.history.undo();
  }

  redo() {
    if (this.#gesture || this.#committing) return false;
    return this.history.redo();
  }

  /** Back to the positions as loaded (undoable). */
  reset() {
    const document = this.#requireDocument();
    if (this.#gesture || this.#committing || document.positions === document.loadedPositions) return false;
    const before = document.positions;
    this.#restorePositions(document.loadedPositions);
    this.history.push(
      new PositionsCommand('Reset to loaded mesh', before, document.loadedPositions, (p) => this.#restorePositions(p)),
    );
    return true;
  }

  #applyPositions(positions) {
    this.#dropPattern();
    this.document.positions = positions;
    this.emit('positions', { positions, live: false });
    this.emit('change', { reason: 'positions' });
  }

  // Undo, redo and reset: the worker's rest mesh follows (a copy is sent,
  // because the history keeps the original).
  #restorePositions(positions) {
    const copy = positions.slice();
    this.#client.request(Request.setPositions, { positions: copy }, [copy.buffer]).catch((error) => {
      this.#reportError(error, 'The solver could not restore the positions');
    });
    this.#applyPositions(positions);
  }

  // ---- flattening ----------------------------------------------------------

  /**
   * Flattens the committed mesh (or its selection) into a garment pattern;
   * options as Session.flatten (wasm/CONTRACT.md). The mesh and its history
   * are untouched; the result is kept as `pattern` until the mesh changes.
   */
  async flatten(options = {}) {
    const document = this.#requireDocument();
    if (this.#gesture || this.#committing) {
      throw this.#reportError(Object.assign(new Error('an edit is in progress'), { code: 'bad-parameter' }), 'Flatten');
    }
    if (!options || typeof options !== 'object') {
      throw this.#reportError(Object.assign(new Error('options must be an object'), { code: 'bad-parameter' }), 'Flatten');
    }
    if (options.patch === 'selection') {
      if (document.selectionCount === 0) {
        const error = new Error('nothing is selected: paint the patch to flatten, or flatten the whole mesh');
        throw this.#reportError(Object.assign(error, { code: 'bad-parameter' }), 'Flatten');
      }
      this.#syncSelection();
    }
    this.#committing++;
    this.emit('busy', true);
    try {
      const result = await this.#client.request(Request.flatten, { options });
      // Undo, redo and edits wait while this runs (#committing); only a new
      // mesh can have arrived meanwhile.
      if (this.document !== document) return result;
      this.pattern = { ...result, options: { patch: 'mesh', ...options } };
      this.emit('pattern', this.pattern);
      return result;
    } catch (error) {
      throw this.#reportError(error, 'Flatten failed');
    } finally {
      this.#committing--;
      this.emit('busy', this.#committing > 0);
      this.emit('progress', { stage: 'done', message: '' });
    }
  }

  /** The last flattening as an SVG or DXF file (bytes). */
  async exportPattern(format, options = {}) {
    try {
      if (!this.pattern) {
        throw Object.assign(new Error('there is no pattern: flatten the mesh first'), { code: 'bad-parameter' });
      }
      const { bytes } = await this.#client.request(Request.exportPattern, { format, mmPerUnit: options.mmPerUnit ?? 1 });
      return bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
    } catch (error) {
      throw this.#reportError(error, `Pattern export as ${String(format).toUpperCase()} failed`);
    }
  }

  #dropPattern() {
    if (!this.pattern) return;
    this.pattern = null;
    this.emit('pattern', null);
  }

  // ---- export --------------------------------------------------------------

  async export(format) {
    try {
      const document = this.#requireDocument();
      const baseName = document.name.replace(/\.[^.]+$/, '') || 'anisoform';
      return await exportMesh(format, document.positions, document.triangles, baseName);
    } catch (error) {
      throw this.#reportError(error, `Export as ${format} failed`);
    }
  }

  // ---- helpers -------------------------------------------------------------

  #requireDocument() {
    if (!this.document) throw Object.assign(new Error('no mesh is loaded yet'), { code: 'bad-parameter' });
    return this.document;
  }

  /**
   * The one way an error reaches the user: emits 'error' (the banner and the
   * API's event) once per error, whoever catches it, and returns the Error
   * to throw on. `context` says what was refused ("Stretch was not applied").
   */
  report(error, context) {
    return this.#reportError(error, context);
  }

  // Emits the error in plain words and returns an Error to throw, with the
  // code of the layer that raised it (core codes pass through unchanged).
  #reportError(error, context) {
    if (this.#reported.has(error)) return error;
    const code = error?.code ?? 'internal';
    const detail = error?.message ?? String(error);
    const message = context ? `${context}: ${detail}` : detail;
    this.emit('error', { code, message });
    const reported = Object.assign(new Error(message), { code, cause: error });
    this.#reported.add(reported);
    return reported;
  }
}

// A load error in plain words: the core already names the file ("x.obj:
// ..."), and the context says it again, so the detail drops it; it also says
// that the mesh on screen stays.
function loadError(error, name, current) {
  let detail = error?.message ?? String(error);
  for (const prefix of [`${name}: `, `'${name}': `]) {
    if (name && detail.startsWith(prefix)) detail = detail.slice(prefix.length);
  }
  detail = detail.replace(/\.?\s*$/, '.');
  if (current) detail += ` The current mesh (${current.name}) is unchanged.`;
  return Object.assign(new Error(detail), { code: error?.code ?? 'internal' });
}

function foldOverWarning(count) {
  return `${count} triangle${count === 1 ? '' : 's'} folded over: reduce the amount or the falloff.`;
}

const TRANSFORM_NAMES = { scale: 'Stretch', shear: 'Shear', rotate: 'Rotate', twist: 'Twist' };
const METHOD_NAMES = { anarap: 'AnARAP', andefgrad: 'AnDefGrad', arap: 'ARAP', linear: 'Linear' };

export function describeEdit(op) {
  if (op.method === 'arap' && op.move) return 'Move (ARAP)';
  const kind = Object.keys(op.transform ?? {}).find((key) => key in TRANSFORM_NAMES) ?? 'scale';
  return `${TRANSFORM_NAMES[kind]} (${METHOD_NAMES[op.method] ?? op.method})`;
}
