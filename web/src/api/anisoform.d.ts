// Public API of the Anisoform page: `window.anisoform`.
// The same object drives the page's own panels, the Playwright tests and
// embedders. Coordinates are model units; pixels are CSS pixels of the
// viewport canvas, origin top-left, y down.

// The request and result shapes are the WASM module's, declared once in
// wasm/js/anisoform-wasm.d.ts (copied beside the module into web/src/wasm/ by
// the build) and parsed by the core; the page adds only what needs its view:
// a screen drag given in canvas pixels, the camera filled in by the page.
import type {
  ConstraintsDirection,
  DocumentSelectStep,
  CurvatureDirection,
  DeformOp as SessionDeformOp,
  DeformResult as SessionDeformResult,
  EditDocument,
  FlattenOptions,
  FlattenResult as SessionFlattenResult,
  GlobalDirection,
  PatternOptions,
  Region,
  SelectOptions,
  Transform,
  Vec3,
} from '../wasm/anisoform-wasm';

// What an embedder's calls are written in (setRegion's steps, exportPattern's
// options, the document's ops and regions, each direction).
export type {
  ConstraintsDirection, CurvatureDirection, DocumentOp, DocumentRegion, DocumentSelectStep, FlattenMetrics, FlattenOptions,
  GlobalDirection, PatternOptions, Region, SelectOptions, Transform, Vec3,
} from '../wasm/anisoform-wasm';

export type Pixel = [number, number];

export interface MeshCounts {
  vertices: number;
  triangles: number;
}

export interface MeshInfo extends MeshCounts {
  components: number;
  boundaryLoops: number;
  /** The unit the coordinates are most likely in, guessed by the core from the mesh's size (the pattern files' default scale). */
  unitGuess: { name: 'm' | 'cm' | 'mm'; mmPerUnit: number };
}

/** A drag on the canvas; the surface point under `from` (or `anchor`) fixes its depth. */
export interface PageScreenDirection {
  type: 'screen';
  from: Pixel;
  to: Pixel;
  anchor?: Vec3;
}

export type Direction = GlobalDirection | CurvatureDirection | PageScreenDirection | ConstraintsDirection;

/**
 * The session's op with the page's directions; 'arap' without handles moves the fully selected
 * vertices by `move` and pins the unselected ones. Committed in full (no preview).
 */
export type DeformOp = Omit<SessionDeformOp, 'direction' | 'preview' | 'warmStart'> & { direction?: Direction };

/**
 * What setParameter changes in an op: `transform` is merged into the op's, `method`, `direction`
 * and `move` replace its own (a screen drag has no place in a stored op: give its 3D vector as a global direction).
 */
export interface OpPatch {
  transform?: Transform;
  method?: SessionDeformOp['method'];
  direction?: GlobalDirection | CurvatureDirection | ConstraintsDirection;
  /** An ARAP drag's offset of the dragged part (method 'arap'). */
  move?: Vec3;
}

/** `converged`: false when the solve stopped at its iteration cap (`maxIterations`) before the tolerance. */
export type DeformResult = Pick<SessionDeformResult, 'iterations' | 'energy' | 'ms' | 'inverted' | 'converged'>;

export type FlattenResult = Pick<SessionFlattenResult,
  'uv' | 'metrics' | 'triangles' | 'compressionError' | 'crossError' | 'grainlines'>;

export interface Hit {
  point: Vec3;
  normal: Vec3;
  triangle: number;
  /** The triangle corner nearest to the hit. */
  vertex: number;
}

export interface CameraState {
  /** Column-major 4x4 matrices, as three.js `Matrix4.elements`. */
  view: number[];
  projection: number[];
  viewport: [number, number, number, number];
  position: Vec3;
  target: Vec3;
}

export interface ChangeEvent {
  reason: 'load' | 'positions' | 'selection' | 'document';
}
/** A copy of the positions shown (and of the heat map's values, when it is on): the listener's own. */
export interface PositionsEvent {
  positions: Float32Array;
  /** True for a preview (a drag, a slider, a typed amount) not yet committed. */
  live: boolean;
  /** The heat map's distortion per vertex against the mesh as loaded, when the heat map is on. */
  distortion?: Float32Array;
}
/**
 * The edit document (docs/document.schema.json; wasm/js/anisoform-wasm.d.ts
 * EditDocument declares its objects): the base mesh, named regions and the
 * ordered, resolved ops. Replaying it (api.open, Session.replay in Node,
 * `anisoform replay`) gives the same positions.
 */
export type { EditDocument } from '../wasm/anisoform-wasm';
/**
 * Every refusal and failure, once: a rejected load, select, deform, flatten,
 * export or document change (its promise rejects with the same message), and
 * what the page's own buttons could not do. The message says what to do about it.
 */
export interface ErrorEvent {
  /**
   * 'storage': an autosave failed (the work in the page is kept). 'display': the 3D view lost its
   * WebGL context (a browser keeps about 16 a page); the work is kept, and the view is drawn again
   * when the browser restores the context.
   */
  code: 'bad-parameter' | 'bad-mesh' | 'bad-file' | 'numerical' | 'internal' | 'out-of-memory' | 'storage' | 'display';
  message: string;
}
/**
 * What a rejected promise of the api holds: an Error with the code of its 'error' event, or
 * 'cancelled' for a solve stopped by cancel() or by the modeller's dispose() (which is no
 * failure: no 'error' event).
 */
export interface AnisoformError extends Error {
  code: ErrorEvent['code'] | 'cancelled';
}
export interface ProgressEvent {
  /**
   * 'init' the solver loading; 'read' a file being read, 'parse' and 'load' its mesh checked and
   * kept; 'factorize' the solver prepared for a shape; 'solve' an edit solved; 'flatten' a
   * flattening; 'restart' the solver started again after a cancel; 'done' nothing running.
   */
  stage: 'init' | 'read' | 'parse' | 'load' | 'factorize' | 'solve' | 'flatten' | 'restart' | 'done';
  message: string;
  /** In [0, 1] when known. */
  fraction?: number;
}

export interface Anisoform {
  readonly version: string;
  /** Resolves when the WASM solver and the default mesh are loaded and drawn. */
  readonly ready: Promise<void>;
  /** Loads OBJ, PLY, STL, OFF or GLB; on failure rejects and keeps the current mesh. */
  load(source: File | Blob | ArrayBuffer, name: string): Promise<MeshCounts>;
  info(): MeshInfo;
  /**
   * A copy: xyz per vertex, of the committed shape (the document's last
   * state). A live preview (a drag, or setParameter with `preview: true`)
   * is not in it until committed: its shapes come in 'positions' events
   * with `live: true`.
   */
  positions(): Float32Array;
  /**
   * Selects by the core's rule (in the solver worker) as one undoable step;
   * resolves with the number of vertices with weight > 0. Rejects (and emits
   * 'error') with code 'bad-parameter' for a bad region or option.
   */
  select(region: Region, options?: SelectOptions): Promise<number>;
  /** A copy: weight per vertex in [0, 1]. */
  selection(): Float32Array;
  /** One committed, undoable edit. An empty selection edits the whole mesh. */
  deform(op: DeformOp): Promise<DeformResult>;
  /**
   * Stops the solve in progress at once (a committed edit, a re-run of the
   * document, a flattening; the UI's Cancel and Esc): its promise rejects with
   * code 'cancelled', and the mesh, the document and the history stay as they
   * were before it. With no solve, it drops a preview of setParameter (`{preview: true}`) that was
   * not committed: the document's shape shows again. False when there was neither.
   */
  cancel(): boolean;
  /**
   * Undo/redo move over the document's ops (and selection steps). An undo of
   * an op re-runs the document's solve in the background: true when it
   * started; false when there is nothing to undo/redo, a drag is on, or a
   * solve (an edit, or an earlier undo's re-run) still runs (a notice says
   * so). To take back several steps, call again after each one's 'document'
   * event.
   */
  undo(): boolean;
  redo(): boolean;
  /** Back to the mesh as loaded: the ops are cleared (undoable; the autosave keeps the mesh, without them); false if there were none. */
  reset(): boolean;
  /** The edit document (a copy): the ops done so far. */
  document(): EditDocument;
  /**
   * Replays a document on the current mesh, or on `meshBytes`: the file `meshName` (its extension
   * says the format; default document.mesh.name), whose name the opened document then records. Any
   * error (version, region, amounts, a mesh whose hash differs, bad JSON) rejects with its code,
   * naming the op or field (a mesh refused by its hash is named as the document names it), and the
   * current work is kept.
   */
  open(document: EditDocument, meshBytes?: ArrayBuffer | Uint8Array, meshName?: string): Promise<void>;
  /**
   * Merges `transform` into op `opId`'s (and replaces its `method`, `direction` and `move`, if given) and
   * re-solves from that op's input, re-running the later ops.
   * {preview: true}: a live preview only (a slider being dragged), the document unchanged; on the last
   * op a warm-started solver iteration (while no new value comes for 120 ms, the value goes on
   * iterating for up to 3 s, each step a live 'positions' event), on an earlier op a quick replay of
   * the ops from it on (each a few-iteration preview). Call again without it on release to commit the
   * value (a step of the history). Resolves: a commit with nothing; a preview of the last op with
   * its solve's {iterations, ms}, of an earlier op with {replayed} (the ops re-run); a preview a
   * newer value superseded with null.
   */
  setParameter(opId: string, patch: OpPatch, options?: { preview?: boolean }):
    Promise<void | null | { iterations: number; ms: number } | { replayed: number }>;
  /** Toggles an op off or on; the later ops re-run. A step of the history (undo turns it back). */
  setOpEnabled(opId: string, enabled: boolean): Promise<void>;
  /** Deletes an op; the later ops re-run on its input. A step of the history (undo puts it back). */
  removeOp(opId: string): Promise<void>;
  /** Moves an op to place `index` (0-based) of the list; the ops from the first place that changed re-run. A step of the history. */
  moveOp(opId: string, index: number): Promise<void>;
  /** Names an op (its label in the Edits list and in saved edits; 1 to 80 characters). Nothing re-runs. A step of the history. */
  renameOp(opId: string, name: string): Promise<void>;
  /**
   * Gives an op the region of these select steps (as a document's region holds them: a soft border
   * is a step's `falloff`); the op and the later ones re-run. A step of the history.
   */
  setRegion(opId: string, steps: DocumentSelectStep[]): Promise<void>;
  export(format: 'obj' | 'ply' | 'stl' | 'glb'): Promise<ArrayBuffer>;
  /** A garment pattern of the mesh or its selection; the mesh and history are untouched. */
  flatten(options?: FlattenOptions): Promise<FlattenResult>;
  /**
   * The last flattening as a pattern file in millimetres (SVG, or DXF R12); rejects if there is none.
   * options.mmPerUnit defaults to the guessed unit of the mesh (info().unitGuess: m 1000, cm 10, mm 1).
   */
  exportPattern(format: 'svg' | 'dxf', options?: PatternOptions): Promise<ArrayBuffer>;
  /** Returns a function that removes the listener. */
  on(event: 'change', callback: (event: ChangeEvent) => void): () => void;
  on(event: 'error', callback: (event: ErrorEvent) => void): () => void;
  on(event: 'progress', callback: (event: ProgressEvent) => void): () => void;
  on(event: 'positions', callback: (event: PositionsEvent) => void): () => void;
  /** A copy of the edit document, as document() gives, whenever it changes. */
  on(event: 'document', callback: (document: EditDocument) => void): () => void;
  /** The surface under a canvas pixel, or null. */
  pick(pixel: Pixel): Hit | null;
  camera(): CameraState;
  /** Fits the camera to the whole mesh (bounding sphere), keeping the view direction. */
  frame(): void;
}

declare global {
  interface Window {
    anisoform: Anisoform;
    /**
     * The standalone site's modeller: stop() ends it as leaving the page
     * does (window.anisoform goes with it); start() ends it and starts a new
     * one as a reload does, without loading the code again, and resolves
     * when the new one is ready.
     */
    anisoformSite: { start(): Promise<void>; stop(): void };
  }
}
