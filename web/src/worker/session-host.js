// Inside the worker: one WASM Session and a handler per protocol request
// (protocol.js). Results hand out copies of the session's heap views: a view
// detaches when WASM memory grows, and a copy can be transferred to the page.
import { readFileBytes } from '../io/read-file.js';
import { Request } from './protocol.js';
import { simplifiedMesh } from './display-proxy.js';
import { meshDisplay } from './mesh-display.js';

const PROGRESS_AFTER_MS = 150;
const PROGRESS_EVERY_MS = 100;
const STAGE_MESSAGES = {
  load: 'Reading the mesh',
  factorize: 'Preparing the solver',
  solve: 'Solving',
  flatten: 'Flattening the patch',
};

export class SessionHost {
  /**
   * @param {object} wasm        the module from createAnisoformWasm()
   * @param {(stage: string, message: string, fraction?: number) => void} reportProgress
   */
  constructor(wasm, reportProgress) {
    this.session = new wasm.Session();
    this.reportProgress = reportProgress;
    this.session.setProgress((stage, fraction) => this.#coreProgress(stage, fraction));
    this.handlers = {
      [Request.loadFile]: (payload) => this.loadFile(payload),
      [Request.setMesh]: (payload) => this.setMesh(payload),
      [Request.prepareStep]: () => this.prepareStep(),
      [Request.simplify]: (payload) => this.simplify(payload),
      [Request.select]: (payload) => this.select(payload),
      [Request.setSelection]: (payload) => this.setSelection(payload),
      [Request.deform]: (payload) => this.deform(payload),
      [Request.distortion]: (payload) => this.distortion(payload),
      [Request.cancel]: () => this.cancel(),
      [Request.setPositions]: (payload) => this.setPositions(payload),
      [Request.directionField]: (payload) => this.directionField(payload),
      [Request.exportMesh]: (payload) => this.exportMesh(payload),
      [Request.surfaceAttributes]: () => this.surfaceAttributes(),
      [Request.flatten]: (payload) => this.flatten(payload),
      [Request.exportPattern]: (payload) => this.exportPattern(payload),
      [Request.resolveOp]: ({ op }) => ({ result: { op: this.session.resolveOp(op) }, transfer: [] }),
      [Request.replay]: (payload) => this.replay(payload),
      [Request.selectDocumentRegion]: (payload) => this.selectDocumentRegion(payload),
    };
  }

  /** Frees the WASM session (its mesh, factorizations and history). */
  dispose() {
    this.session.delete();
    this.session = null;
  }

  /** @returns {{result: object, transfer: Transferable[]}}, or a promise of it */
  handle(kind, payload) {
    const handler = this.handlers[kind];
    if (!handler) throw new Error(`unknown request '${kind}'`);
    // Progress is shown for the calls a user waits for, not for the live
    // previews of a drag (a deform) or of a slider on an earlier op (a replay).
    const livePreview = (kind === Request.deform && payload.op?.preview) || (kind === Request.replay && payload.preview);
    // The parts of one preparation count as one call: a long one shows its
    // progress from its first part on.
    const started = (kind === Request.prepareStep && this.#preparingSince) || performance.now();
    const label = kind === Request.replay ? payload.label : undefined;
    this.#progress = { started, posted: -Infinity, stage: null, shown: !livePreview, label };
    return handler(payload);
  }

  #progress = null;
  /** When the unfinished preparation's first part started, or null. */
  #preparingSince = null;

  // Progress (stage, fraction) of the core, or of reading a file, as the
  // page's: only once a call has run for PROGRESS_AFTER_MS (a quick one shows
  // none), then at most every PROGRESS_EVERY_MS, and always a stage's start
  // and end.
  #coreProgress(stage, fraction, message = STAGE_MESSAGES[stage] ?? stage) {
    const progress = this.#progress;
    if (!progress?.shown) return;
    const now = performance.now();
    if (now - progress.started < PROGRESS_AFTER_MS) return;
    const edge = stage !== progress.stage || fraction === 0 || fraction === 1;
    if (!edge && now - progress.posted < PROGRESS_EVERY_MS) return;
    progress.stage = stage;
    progress.posted = now;
    this.reportProgress(stage, progress.label ? `${progress.label}: ${message}` : message, fraction);
  }

  // A picked File is read here (a promise), a buffer is loaded at once. The
  // bytes are kept as a Blob beside the edit document, for the autosave
  // (op-stack.js): a File is that Blob already; a buffer is copied here, off
  // the page's thread.
  loadFile({ source, name }) {
    if (!(source instanceof Blob)) return this.#loadBytes(source, name, new Blob([source]));
    const progress = (fraction) => this.#coreProgress('read', fraction, `Reading ${name}`);
    return readFileBytes(source, progress).then((bytes) => this.#loadBytes(bytes, name, source));
  }

  #loadBytes(bytes, name, sourceBytes) {
    this.reportProgress('parse', `Reading ${name}`);
    const info = this.session.loadMesh(new Uint8Array(bytes), name);
    const payload = this.meshPayload(info, true);
    payload.result.sourceBytes = sourceBytes;
    return payload;
  }

  setMesh({ positions, triangles, weld, display = true }) {
    this.reportProgress('parse', 'Checking the mesh');
    const info = this.session.setMesh(positions, triangles, { weld });
    const payload = this.meshPayload(info, display);
    if (weld) {
      // Where the arrays' vertices went: a GLB export writes the edited shape back through it.
      const inputVertexMap = this.session.inputVertexMap();
      payload.result.inputVertexMap = inputVertexMap;
      payload.transfer.push(inputVertexMap.buffer);
    }
    return payload;
  }

  // display: the mesh will be shown, so its normals and picking BVH come
  // along (mesh-display.js); a restart's seed puts back a mesh already shown.
  meshPayload(info, display) {
    const positions = this.session.positions().slice();
    const triangles = this.session.triangles().slice();
    const exact = this.session.positionsExact();
    const hash = this.session.meshHash();
    const result = { info, positions, triangles, exact, hash };
    const transfer = [positions.buffer, triangles.buffer, exact.buffer];
    if (display) {
      this.reportProgress('parse', 'Building the picking structure');
      const { normals, bvh, transfer: displayTransfer } = meshDisplay(positions, triangles);
      Object.assign(result, { normals, bvh });
      transfer.push(...displayTransfer);
    }
    return { result, transfer };
  }

  // The edit document's ops [from, to) through the core's replay; the result
  // is the session's rest pose, returned as float32 (to draw) and doubles (to cache).
  replay({ document, from, to, preview = false, distortion }) {
    const summary = this.session.replay(document, { from, to, preview });
    const positions = this.session.positions().slice();
    const exact = this.session.positionsExact();
    const { replayed, skipped, warnings } = summary;
    const result = { positions, exact, summary: { replayed, skipped, warnings, last: summary.last && plainStats(summary.last) } };
    const transfer = [positions.buffer, exact.buffer];
    if (distortion) {
      result.distortion = this.session.distortion(distortion, 'loaded');
      transfer.push(result.distortion.buffer);
    }
    return { result, transfer };
  }

  // One part of the background preparation (Request.prepareStep); its first
  // part announces it, however short.
  prepareStep() {
    if (!this.#preparingSince) this.reportProgress('factorize', 'Preparing the solver');
    const share = this.session.prepareStep();
    this.#preparingSince = share < 1 ? this.#progress.started : null;
    return { result: { share }, transfer: [] };
  }

  async simplify({ triangles }) {
    const simplified = await simplifiedMesh(this.session.positions().slice(), this.session.triangles().slice(), triangles);
    return { result: simplified, transfer: [simplified.vertices.buffer, simplified.triangles.buffer] };
  }

  select({ region, options }) {
    const count = this.session.select(region, options);
    const weights = this.session.selection().slice();
    return { result: { count, weights }, transfer: [weights.buffer] };
  }

  selectDocumentRegion({ document, opId }) {
    const count = this.session.selectDocumentRegion(document, opId);
    const weights = this.session.selection().slice();
    return { result: { count, weights }, transfer: [weights.buffer] };
  }

  setSelection({ weights }) {
    return { result: { count: this.session.setSelection(weights) }, transfer: [] };
  }

  deform({ op, commit, distortion }) {
    const stats = this.session.deform(op);
    if (commit) this.session.commit();
    const positions = this.session.positions().slice();
    const result = { positions, stats: plainStats(stats) };
    const transfer = [positions.buffer];
    if (distortion) {
      result.distortion = this.session.distortion(distortion, 'loaded');
      transfer.push(result.distortion.buffer);
    }
    return { result, transfer };
  }

  distortion({ distortion }) {
    const values = this.session.distortion(distortion, 'loaded');
    return { result: { values }, transfer: [values.buffer] };
  }

  cancel() {
    this.session.cancel();
    const positions = this.session.positions().slice();
    return { result: { positions }, transfer: [positions.buffer] };
  }

  setPositions({ positions }) {
    this.session.setPositions(positions);
    return { result: {}, transfer: [] };
  }

  directionField({ direction }) {
    const field = this.session.directionField(direction).slice();
    return { result: { field }, transfer: [field.buffer] };
  }

  exportMesh({ format }) {
    const bytes = this.session.exportMesh(format);
    return { result: { bytes }, transfer: [bytes.buffer] };
  }

  surfaceAttributes() {
    const attributes = this.session.surfaceAttributes();
    const transfer = [attributes.cornerUv, attributes.colors].filter(Boolean).map((array) => array.buffer);
    return { result: attributes, transfer };
  }

  flatten({ options }) {
    this.reportProgress('flatten', 'Flattening the patch');
    const result = this.session.flatten(options);
    const arrays = [result.uv, result.triangles, result.compressionError, result.crossError, result.vertexError,
      result.outlinePieces, ...result.outlines];
    return {
      result: {
        uv: result.uv,
        triangles: result.triangles,
        compressionError: result.compressionError,
        crossError: result.crossError,
        vertexError: result.vertexError,
        grainlines: result.grainlines.map((g) => [g[0], g[1]]),
        outlines: result.outlines,
        outlinePieces: result.outlinePieces,
        metrics: { ...result.metrics },
      },
      transfer: [...new Set(arrays.map((array) => array.buffer))], // outlines may share one
    };
  }

  exportPattern({ format, mmPerUnit }) {
    const bytes = this.session.exportPattern(format, { mmPerUnit });
    return { result: { bytes }, transfer: [bytes.buffer] };
  }
}

// Embind value objects may carry extra fields; the page gets a plain object.
function plainStats(stats) {
  return {
    iterations: stats.iterations,
    energy: stats.energy,
    ms: stats.ms,
    factorizations: stats.factorizations,
    converged: stats.converged,
    directionsFilled: stats.directionsFilled,
    inverted: stats.inverted,
  };
}
