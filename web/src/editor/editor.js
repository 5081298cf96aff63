// The editor: the page's model of an editing session, between the UI/API and
// the solver worker. It owns the mesh document and the history, and hands the
// rest to its parts: loading (mesh-loader.js), the selection
// (selection-state.js), the live drag (gesture-controller.js), committed
// edits and their undo (edit-commits.js), the garment pattern
// (pattern-state.js) and export (mesh-export.js). It announces changes as
// events:
//   'mesh'       a new mesh was loaded (payload: MeshDocument)
//   'positions'  {positions, live, distortion?}: committed positions, or a
//                live preview; distortion: the heat map's values (heatMapKind)
//                when the worker sent them along
//   'selection'  {weights, count, live}: committed weights, or a brush stroke in progress
//   'history'    {canUndo, canRedo, undoLabel, redoLabel}
//   'stats'      {ms, iterations, live, factorizations, converged}: converged false
//                when the solve ended at its iteration cap (a live preview's one does)
//   'progress'   {stage, message, fraction?}; stage 'done' ends it
//   'busy'       boolean: a committed edit is being solved
//   'gesture'    boolean: a live edit started or ended
//   'error'      {code, message}: every refusal and failure, in plain words
//                that say what to do (report() is the one way in)
//   'loading'    {name}: a load started; old messages no longer apply
//   'notice'     {message, details, source}: what a load repaired or found
//                (source 'load'; plain words; details: the full list, one
//                sentence each), or that the user stopped a solve (source
//                'cancel', until something committed changes again)
//   'warning'    {message, source}: a committed edit folded triangles over
//                (source 'edit'), or the last flattening is not usable as
//                one piece (source 'flatten'); a live preview's folds are
//                its 'stats' {live, inverted}
//   'pattern'    the last flattening (FlattenPayload plus its options), or null
//                when the mesh, its positions or the flattened selection changed
//   'document'   the edit document changed (document/op-stack.js: an op committed,
//                undone, toggled or re-parameterised, a document opened)
//   'change'     {reason}: anything committed changed (load, edit, selection, undo)
import { History } from '../commands/history.js';
import { EventEmitter } from '../shared/event-emitter.js';
import { Request } from '../worker/protocol.js';
import { EditCommits } from './edit-commits.js';
import { describeEdit, reporter } from './edit-wording.js';
import { GestureController } from './gesture-controller.js';
import { MeshDocument } from './mesh-document.js';
import { exportMeshFile } from './mesh-export.js';
import { fileNameOf, loadError, readMesh } from './mesh-loader.js';
import { PatternState } from './pattern-state.js';
import { describeProblems } from './problem-summary.js';
import { SelectionState } from './selection-state.js';
import { toSolverOp } from './solver-op.js';
import { badParameter, gestureInProgressError, supersededLoadError } from '../shared/errors.js';

/** How long the solver must be idle after a commit before it factorizes the new shape. */
const PREPARE_AFTER_COMMIT_MS = 400;
/** How often a preparation paused for the user's work (#solverInUse) looks again. */
const PREPARE_RETRY_MS = 100;

export class Editor extends EventEmitter {
  /** @type {MeshDocument|null} */
  document = null;
  history = new History();
  /** The viewer's camera and picking, for screen-space directions (attachView). */
  view = null;
  /** The heat map's distortion kind ('area'|'stretch') that edits send back, or null. */
  heatMapKind = null;
  #client;
  #busy = 0;
  // Called when the operation running ends (afterOperation).
  #whenEnded = [];
  /**
   * Cancels so far: a commit asked for before a cancel, not yet sent to the
   * worker (queued, or between its requests), is cancelled too (op-stack.js).
   */
  cancels = 0;
  /** Whether the solve running was cancelled (until a solve ends or starts). */
  #cancelling = false;
  #prepareTimer = 0;
  #preparation = 0; // counts prepareSolver() calls: the latest one goes on
  #prepared = Promise.resolve();
  #meshBound = [];
  #loadRequests = 0;
  #loadChain = Promise.resolve();
  #report = reporter((event, payload) => this.emit(event, payload));
  #gestures;
  #patterns;
  #commits;

  constructor(client) {
    super();
    this.#client = client;
    this.#gestures = new GestureController({ editor: this, client });
    this.#patterns = new PatternState({ editor: this, client });
    this.#commits = new EditCommits({ editor: this, client, dropPattern: () => this.#patterns.drop() });
    this.selectionState = new SelectionState({ editor: this, client, beforeChange: () => this.#patterns.selectionChanged() });
    client.on('progress', (progress) => this.emit('progress', progress));
    this.history.on('change', (state) => this.emit('history', state));
    this.history.on('step', (step) => this.emit('step', step));
  }

  attachView(view) {
    this.view = view;
  }

  async start() {
    await this.#client.request(Request.init);
  }

  get busy() {
    return this.#busy > 0;
  }

  /**
   * Esc, or Cancel beside the progress: stops the solve in progress at once
   * (a committed edit, a replay, a flattening). The mesh, the document and
   * the history stay as they were before it; the solver comes back with that
   * state in the background. False when nothing is being solved.
   */
  cancelSolve() {
    // A solve already cancelled, still unwinding, is not cancelled again
    // (nor its fresh worker restarted again).
    if (!this.busy || !this.document || this.#cancelling) return false;
    this.#cancelling = true;
    this.cancels++;
    const document = this.document;
    this.selectionState.forget(); // the new worker has none
    this.#patterns.drop(); // the last flattening was the old worker's
    this.ops.restartSolver((seed) => this.#client.restart(seed)).then(
      () => this.document === document && this.prepareSolver(),
      // 'cancelled': a later cancel restarted it again, and reports for itself.
      (error) => {
        if (error.code === 'cancelled' || this.document !== document) return;
        this.emit('progress', { stage: 'done', message: '' }); // no "Restarting" left showing
        this.report(error, 'The solver could not be restarted');
      },
    );
    return true;
  }

  /** Whether this modeller was disposed (its solver worker ended). */
  get disposed() {
    return this.#client.disposed;
  }

  /** Marks a committed solve in progress; call the returned function when it ends. */
  beginBusy() {
    this.#busy++;
    this.#cancelling = false;
    this.emit('busy', true);
    return () => {
      this.#busy--;
      this.#cancelling = false;
      this.emit('busy', this.#busy > 0);
      for (const callback of this.#whenEnded.splice(0)) callback();
    };
  }

  /**
   * Calls `callback` once the committed solve running has ended (its busy
   * released; another queued may follow), or at once when none runs.
   */
  afterOperation(callback) {
    if (this.busy) this.#whenEnded.push(callback);
    else callback();
  }

  /** The edit document and its op stack (document/op-stack.js). */
  get ops() {
    return this.#commits.ops;
  }

  get gestureActive() {
    return this.#gestures.active;
  }

  /**
   * Throws while a drag on the view edits the mesh: what would change under
   * it (the selection, the ops, an opened document) or read the worker's
   * live preview as the committed mesh (an edit, an export) waits for its
   * end. (select, removeOp and open were taken mid-drag, and the released
   * drag committed on another region or base pose than it showed.)
   */
  refuseDuringGesture() {
    if (this.gestureActive) throw gestureInProgressError();
  }

  /** The last flattening (see PatternState), or null. */
  get pattern() {
    return this.#patterns.pattern;
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

  /**
   * Loads a File, Blob or ArrayBuffer; on failure the current mesh stays.
   * Loads run one after another, and one asked for while another waits or
   * runs replaces the waiting one (rejected 'cancelled'): the mesh shown,
   * and the worker's, is the last asked for (a product page's own load right
   * after its modeller's starting mesh ended with the starting mesh).
   */
  /** How many loads were asked for so far (a host's own, started later, wins over one of its downloads). */
  get loadsAsked() {
    return this.#loadRequests;
  }

  load(source, name) {
    const request = ++this.#loadRequests;
    const run = () => {
      if (request !== this.#loadRequests) throw supersededLoadError();
      return this.#load(source, name);
    };
    const loading = this.#loadChain.then(run, run);
    this.#loadChain = loading.catch(() => {});
    return loading;
  }

  async #load(source, name) {
    try {
      name = fileNameOf(source, name);
      this.emit('loading', { name });
      const payload = await readMesh(this.#client, source, name, (progress) => this.emit('progress', progress));
      this.#adopt(payload, name);
      return { vertices: payload.info.vertices, triangles: payload.info.triangles };
    } catch (error) {
      this.emit('progress', { stage: 'done', message: '' });
      throw this.report(loadError(error, typeof name === 'string' ? name : '', this.document), `Could not load ${name || 'the file'}`);
    }
  }

  // The one place where a new mesh replaces the old one: everything tied to
  // the old mesh's vertices (the live edit, the pattern and its heat map, the
  // selection, the history, the arrows and whatever else bindToMesh named)
  // is dropped before the new mesh is announced.
  #adopt(payload, name) {
    const { info, positions, triangles, normals, bvh, gltf } = payload;
    this.#gestures.abandon();
    this.#patterns.drop();
    for (const reset of this.#meshBound) reset();
    this.document = new MeshDocument({ name, positions, triangles, info, display: { normals, bvh }, gltf });
    this.history.clear();
    this.ops.adoptMesh(payload, name);
    // Before the mesh is announced: what its listeners ask of the worker
    // after the preparation (whenPrepared) waits for this one.
    this.prepareSolver();
    this.emit('mesh', this.document);
    const notice = describeProblems(info);
    if (notice) this.emit('notice', { ...notice, source: 'load' });
    this.emit('change', { reason: 'load' });
    // The load's progress ends here; the background factorization shows its
    // own once it runs long (else the bar kept the load's last words, e.g.
    // "Building the picking structure", for the first part of it).
    this.emit('progress', { stage: 'done', message: '' });
  }

  /**
   * After a committed edit, an undo or a redo: prepareSolver once the solver
   * has been idle for PREPARE_AFTER_COMMIT_MS. Not at once: a slider on the op just made
   * (which needs the op's input, whose factorization is kept) would wait
   * behind each part.
   */
  prepareSolverSoon() {
    clearTimeout(this.#prepareTimer);
    const document = this.document;
    const attempt = () => {
      if (this.document !== document || this.#client.disposed) return;
      if (this.#solverInUse()) this.#prepareTimer = setTimeout(attempt, PREPARE_AFTER_COMMIT_MS);
      else this.prepareSolver();
    };
    this.#prepareTimer = setTimeout(attempt, PREPARE_AFTER_COMMIT_MS);
  }

  /**
   * Whether the user's work has the solver now: a commit, replay or
   * flattening (busy), a request waiting for the worker, a drag, a slider's
   * live state. The background preparation waits meanwhile: its parts would
   * come between the requests of one commit (each part up to 0.8 s at 200k
   * vertices) and hold up a drag's previews, which build what they need
   * themselves.
   */
  #solverInUse() {
    return this.busy || this.#client.busy || this.gestureActive || this.ops.live;
  }

  /**
   * Factorizes the worker's rest pose in the background (a new mesh, a
   * committed edit), a part at a time: the page stays usable, a select or an
   * edit asked for meanwhile runs after the part in progress (the worker
   * cannot interrupt one), the next part waits while the user's work has
   * the solver (#solverInUse), and an edit finishes the set-up itself
   * instead of paying for all of it mid-drag. A newer preparation (the
   * next commit's) ends this one.
   */
  prepareSolver() {
    const document = this.document;
    const preparation = ++this.#preparation;
    const current = () => this.document === document && this.#preparation === preparation && !this.#client.disposed;
    const step = () => {
      if (!current()) return undefined;
      if (this.#solverInUse()) return new Promise((resolve) => setTimeout(resolve, PREPARE_RETRY_MS)).then(step);
      return this.#client.request(Request.prepareStep).then(({ share }) => {
        if (share < 1) return step();
        if (current()) this.emit('progress', { stage: 'done', message: 'Ready' });
        return undefined;
      });
    };
    this.#prepared = Promise.resolve().then(step).catch((error) => {
      // 'cancelled': a cancel restarted the worker, and prepares again once it
      // is back. (A disposed modeller is not current: no one to tell.)
      if (current() && error.code !== 'cancelled') this.report(error, 'The solver could not prepare this mesh');
    });
  }

  /**
   * Resolves when the latest preparation has ended (done, failed or
   * overtaken): for work the worker should do after it, not before the
   * user's first select (the moving mesh's simplification, 1 s at 400k
   * triangles).
   */
  whenPrepared() {
    return this.#prepared;
  }

  // ---- selection (selection-state.js) --------------------------------------

  /** The core's selection of a region (Session.select); resolves with the selected count. */
  select(region, options = {}) {
    return this.selectionState.select(region, options);
  }

  /** Commits new weights as one undoable step; returns the selected count. */
  setSelection(weights, label) {
    return this.selectionState.commit(weights, label);
  }

  /** Shows weights of a stroke in progress without committing them. */
  showSelection(weights) {
    this.selectionState.show(weights);
  }

  // ---- deformation ---------------------------------------------------------

  /** One committed, undoable edit; a refusal is reported like a failure. */
  async deform(op, label) {
    let solverOp;
    let document;
    try {
      document = this.requireDocument();
      label ??= describeEdit(op);
      this.refuseDuringGesture();
      solverOp = toSolverOp(op, document, this.view);
    } catch (error) {
      throw this.report(error, `${label ?? 'The edit'} was not applied`);
    }
    return this.commitEdit(document, solverOp, label);
  }

  /** Solves `solverOp` fully and commits it as one undoable step (edit-commits.js). */
  commitEdit(document, solverOp, label) {
    return this.#commits.commit(document, solverOp, label);
  }

  /** Starts a live edit (a drag). Returns false while another edit runs. */
  beginGesture() {
    return this.#gestures.begin();
  }

  /** Shows the edit `op` live; stale results are dropped. */
  updateGesture(op) {
    this.#gestures.update(op);
  }

  /** Ends the live edit and commits its last state (fully solved) as one step. */
  commitGesture(label) {
    return this.#gestures.commit(label);
  }

  /** Esc: drops the live edit; the mesh returns to its committed state. */
  cancelGesture() {
    return this.#gestures.cancel();
  }

  /** Per-vertex unit directions of a direction source, for the glyphs. */
  async directionField(direction) {
    const document = this.requireDocument();
    const solverOp = toSolverOp({ method: 'anarap', direction, transform: {} }, document, this.view);
    const { field } = await this.#client.request(Request.directionField, { direction: solverOp.direction });
    return this.document === document ? field : null;
  }

  /**
   * The core's distortion of the positions the worker holds against the mesh
   * as loaded (Session.distortion, a ratio per vertex); null if the mesh
   * changed meanwhile.
   */
  async distortion(kind) {
    const document = this.requireDocument();
    const { values } = await this.#client.request(Request.distortion, { distortion: kind });
    return this.document === document ? values : null;
  }

  // ---- history -------------------------------------------------------------

  undo() {
    if (this.#client.disposed || this.gestureActive || this.refusedWhileBusy('Undo')) return false;
    return this.history.undo();
  }

  redo() {
    if (this.#client.disposed || this.gestureActive || this.refusedWhileBusy('Redo')) return false;
    return this.history.redo();
  }

  /**
   * Whether a committed solve runs, saying so (a notice) for `what`: undo,
   * redo, the brush and the tools' drags wait for no solve, and instead of
   * doing nothing without a word they say why.
   */
  refusedWhileBusy(what) {
    if (!this.busy) return false;
    this.emit('notice', { message: `${what} waits until the solve has ended: press Esc to cancel it.`, source: 'busy' });
    return true;
  }

  /** Back to the positions as loaded (undoable). */
  reset() {
    return this.#commits.reset();
  }

  // ---- flattening (pattern-state.js) ---------------------------------------

  flatten(options = {}) {
    return this.#patterns.flatten(options);
  }

  exportPattern(format, options = {}) {
    return this.#patterns.export(format, options);
  }

  // ---- export --------------------------------------------------------------

  /** The committed mesh as file bytes (mesh-export.js). */
  async export(format) {
    try {
      const document = this.requireDocument();
      // The worker holds the live preview during a drag, not the committed mesh.
      this.refuseDuringGesture();
      return await exportMeshFile(this.#client, document, format);
    } catch (error) {
      throw this.report(error, `Export as ${format} failed`);
    }
  }

  // ---- helpers -------------------------------------------------------------

  requireDocument() {
    if (!this.document) throw badParameter('no mesh is loaded yet');
    return this.document;
  }

  /**
   * The one way an error reaches the user (edit-wording.js, reporter): emits
   * 'error' once per error and returns the Error to throw on.
   */
  report(error, context) {
    return this.#report(error, context);
  }
}
