// Type declarations of the Anisoform WASM JS layer (anisoform-wasm.mjs): the
// one contract of the module. Every request object below is parsed by the
// core (core/include/anisoform/op.h); an interface tagged `@schema PATH`
// declares exactly the keys the core accepts at PATH, which
// wasm/test/contract.test.mjs checks against the core's op_schema(). Defaults
// named here are the core's (the C++ structs' initializers).
export type ErrorCode = 'bad-parameter' | 'bad-mesh' | 'bad-file' | 'numerical' | 'out-of-memory' | 'internal';

/** Every failure of the module: a code and a message that names the problem. */
export class AnisoformError extends Error {
  readonly name: 'AnisoformError';
  readonly code: ErrorCode;
  constructor(code: ErrorCode, message: string, options?: { cause?: unknown });
}

export type Vec2 = [number, number];
export type Vec3 = [number, number, number];
type Numbers = ArrayLike<number>;

export type ProblemKind =
  | 'empty-mesh' | 'non-finite-coordinate' | 'index-out-of-range' | 'repeated-corner'
  | 'zero-area-triangle' | 'duplicate-face' | 'non-manifold-edge' | 'non-manifold-vertex'
  | 'inconsistent-orientation' | 'unreferenced-vertex';

export interface MeshProblem {
  /** aniso::problem_kind_name */
  kind: ProblemKind;
  /** Vertex or face index, as the kind documents. */
  element: number;
  /** Plain words, naming the element. */
  message: string;
}

export interface MeshInfo {
  vertices: number;
  triangles: number;
  components: number;
  boundaryLoops: number;
  edgeManifold: boolean;
  vertexManifold: boolean;
  consistentlyOriented: boolean;
  degenerateTriangles: number;
  duplicateFaces: number;
  unreferencedVertices: number;
  /** Of the vertices the faces use (shape_bounding_box, mesh.h): an unused vertex does not count. */
  bbox: { min: Vec3; max: Vec3 };
  /** The unit the coordinates are most likely in (guess_model_unit, op.h): m, cm or mm. */
  unitGuess: { name: 'm' | 'cm' | 'mm'; mmPerUnit: number };
  /** Problems the solver works through (the blocking ones make loading fail): the first 1000 of each kind. */
  problems: MeshProblem[];
  /** How many problems of each kind there are (kinds found only), listed in `problems` or not. */
  problemCounts: Partial<Record<MeshProblem['kind'], number>>;
  /** What the reader and the session repaired (triangulated, welded...). */
  notes: string[];
}

/** @schema region.sphere */
export interface Sphere {
  center: Vec3 | Numbers;
  radius: number;
}

/** @schema region.box */
export interface Box {
  min: Vec3 | Numbers;
  max: Vec3 | Numbers;
}

/** @schema region.vertices */
export interface VertexRegion {
  vertices: Numbers;
  /** One weight in [0, 1] per listed vertex (default 1). */
  weights?: Numbers;
}

/** @schema region */
export type Region = { all: true } | { sphere: Sphere } | { box: Box } | VertexRegion;

/** @schema select */
export interface SelectOptions {
  /** Soft border width in model units, measured along edges (default 0). */
  falloff?: number;
  /** replace (default); add = max(old, new); subtract = min(old, 1 - new). */
  mode?: 'replace' | 'add' | 'subtract';
}

/** @schema direction.screen.camera */
export interface ScreenCamera {
  /** World -> camera, column-major (three.js camera.matrixWorldInverse.elements). */
  view: Numbers;
  /** Camera -> clip, column-major (three.js camera.projectionMatrix.elements). */
  projection: Numbers;
  /** [x, y, width, height] in CSS pixels. */
  viewport: Numbers;
  /** The picked surface point, world space. */
  anchor: Vec3 | Numbers;
  /**
   * The surface normal at the anchor (any length). Given, the direction is the tangent vector there whose
   * on-screen image runs along the drag; without it, the drag in the image plane (each element then takes
   * its projection along its normal).
   */
  normal?: Vec3 | Numbers;
}

/** @schema direction.global */
export interface GlobalDirection {
  type: 'global';
  vector: Vec3 | Numbers;
}

/** @schema direction.curvature */
export interface CurvatureDirection {
  type: 'curvature';
  which: 'min' | 'max';
  /** Line-field smoothing steps, 0..1000 (default 10). */
  smoothing?: number;
}

/** @schema direction.screen */
export interface ScreenDirection {
  type: 'screen';
  /** Pixels, y down. */
  from: Vec2 | Numbers;
  to: Vec2 | Numbers;
  camera: ScreenCamera;
}

/** @schema direction.constraint */
export interface DirectionConstraint {
  vertex: number;
  direction: Vec3 | Numbers;
  /** Local amounts (both default 1); if every constraint has them they spread harmonically. */
  su?: number;
  sv?: number;
}

/** @schema direction.constraints */
export interface ConstraintsDirection {
  type: 'constraints';
  constraints: DirectionConstraint[];
}

/** @schema direction.dense */
export interface DenseDirection {
  type: 'dense';
  /** #V*3 directions, used as given (projected per element). */
  directions: Float32Array | number[];
}

/** @schema direction.type */
export type Direction = GlobalDirection | CurvatureDirection | ScreenDirection | ConstraintsDirection | DenseDirection;

/** @schema op.transform.rotate */
export interface Rotate {
  axis: 'n' | 'u' | 'v';
  degrees: number;
}

/** @schema op.transform.twist */
export interface Twist {
  axis: Vec3 | Numbers;
  degreesPerUnit: number;
  /**
   * The angle is 0 here (default: on the line through the selection's weighted centroid, at its
   * lowest point along the axis).
   */
  origin?: Vec3 | Numbers;
}

/** @schema op.transform */
export interface Transform {
  /** su, or [su, sv]: scale along the direction and across it (default 1). */
  scale?: number | [number] | [number, number];
  /**
   * sn: scale along the normal (default 1). The linear method only: AnARAP and
   * AnDefGrad refuse it (their elements' edges lie in the surface, which it
   * leaves as it is); scale across (sv) makes a part thicker.
   */
  thickness?: number;
  shear?: number;
  rotate?: Rotate;
  twist?: Twist;
}

/** @schema op */
export interface DeformOp {
  /** default 'anarap' */
  method?: 'anarap' | 'andefgrad' | 'arap' | 'linear';
  /** default: global, along the longest side of the mesh's bounding box as loaded */
  direction?: Direction;
  transform?: Transform;
  /** Vertices held at their rest positions ('arap' without handles: the unselected ones). */
  pins?: Numbers;
  /** 'arap': vertices moved by `move` and held (default: the fully selected ones, or all). */
  handles?: Numbers;
  move?: Vec3 | Numbers;
  /** AnARAP/ARAP energy elements, default 'spokes'. */
  elements?: 'spokes' | 'spokes-rims';
  /** AnARAP/ARAP iteration cap (default 50). */
  maxIterations?: number;
  /**
   * AnARAP with a rotational part (rotate, twist, shear), METHOD §5. 'coupled' (default): neighbouring
   * rotations are tied together, so the iterations converge to the requested turn like a stretch does.
   * 'steps': the paper's scheme, which has no fixed point: exactly `rotationSteps` steps from the rest pose.
   */
  rotations?: 'coupled' | 'steps';
  /** 'coupled': how strongly neighbouring rotations are tied, 0.0001 to 10000 (default 1; larger keeps the turn more exactly). */
  rotationCoupling?: number;
  /** 'steps': the number of steps from the rest pose (default 1). */
  rotationSteps?: number;
  /** Relative energy change that ends the iterations (default 1e-6). */
  tolerance?: number;
  /**
   * AnARAP/ARAP: how the converging iterations are accelerated, each step kept only if it lowers the
   * energy: 'lbfgs' (default: L-BFGS preconditioned by the Laplacian) or 'anderson' (Anderson
   * acceleration); the same result in several times fewer iterations. 'none': plain local/global.
   * The paper's rotation 'steps' are never accelerated.
   */
  acceleration?: 'lbfgs' | 'anderson' | 'none';
  /** Live preview: at most 4 iterations, warm-started (the 'steps' scheme runs its rotationSteps). */
  preview?: boolean;
  /** Start from the previous result of the same setup (default true). */
  warmStart?: boolean;
}

export interface DeformResult {
  /** Vertices with selection weight > 0. */
  selected: number;
  iterations: number;
  energy: number;
  /** Energy after each iteration (AnARAP / ARAP; empty for AnDefGrad and linear). */
  energyHistory: number[];
  converged: boolean;
  /** Elements whose direction was parallel to the normal, filled from neighbours. */
  directionsFilled: number;
  /** Triangles folded over: normal more than 90° from the rest normal once the local rotation is taken out. */
  inverted: number;
  /** Factorizations so far in this session. */
  factorizations: number;
  precomputeMs: number;
  solveMs: number;
  /** The whole call. */
  ms: number;
  /** What the user should know about the result, in words (e.g. a curvature field without clear directions). */
  warnings: string[];
}

/** @schema flatten */
export interface FlattenOptions {
  /** Wanted stretch su along the direction and sv across it (default [1, 1]; 0.8 = 20 % shrinkage). */
  compress?: number | [number] | [number, number];
  /**
   * Where the wanted direction runs (default: global along the longest side of the current
   * positions' bounding box, as the CLI). Constraint amounts override `compress`.
   */
  direction?: GlobalDirection | ConstraintsDirection;
  /** 'uniform': the industry baseline (flatten isometrically, then scale each piece). */
  baseline?: 'uniform';
  /** 'mesh' (default): every triangle; 'selection': the triangles whose 3 vertices have weight > 0. */
  patch?: 'mesh' | 'selection';
  /** Iteration cap of the ARAP iterations and the stretch refinement together (default 1000). */
  maxIterations?: number;
  /** Relative energy change that ends the iterations (default 1e-8). */
  tolerance?: number;
  /**
   * After the ARAP iterations, minimise the reported errors themselves (default true; README,
   * "Flattening refinement"). false: the paper's local/global result as it is.
   */
  refine?: boolean;
}

/** A part of the patch that needs a dart or a cut (FlattenRegion, flatten.h). */
export interface SuggestedCut {
  /** Its vertices (mesh vertex indices, ascending). */
  vertices: number[];
  /** The region's vertex nearest its centroid: where to point at it. */
  vertex: number;
  /** Area-weighted centroid of its triangles (3D, model units). */
  centroid: [number, number, number];
  /** Area-weighted mean of max(|along / su - 1|, |across / sv - 1|) over its triangles. */
  errorMean: number;
  triangles: number;
}

export interface FlattenMetrics {
  /** Patch triangles and vertices. */
  triangles: number;
  vertices: number;
  components: number;
  boundaryLoops: number;
  /** Folded-over triangles. */
  flipped: number;
  /** How many times the pattern's outline crosses itself (it overlaps itself, with no triangle folded): 0 when it lies flat. */
  outlineCrossings: number;
  /** |achieved along / su - 1|: area-weighted mean and max over the patch. */
  compressionErrorMean: number;
  compressionErrorMax: number;
  /** |achieved across / sv - 1|. */
  crossErrorMean: number;
  crossErrorMax: number;
  /** Area-weighted mean of |A2d / (A3d su sv) - 1|. */
  areaDistortionMean: number;
  /**
   * The fabric's shear: |angle between the pattern images of the direction and its cross direction - 90°|,
   * in degrees, area-weighted mean and max (the errors above measure lengths, not this angle).
   */
  shearDegreesMean: number;
  shearDegreesMax: number;
  /** Triangles whose wanted direction is within 10° of their normal. */
  nearNormalDirections: number;
  iterations: number;
  energy: number;
  converged: boolean;
  /** Wall time of the solve and measuring; the patch's precompute (once per patch and positions) is not included. */
  seconds: number;
  /** Triangles whose direction was normal to them, filled from neighbours. */
  filledDirections: number;
  initialization: 'lscm' | 'tutte';
  method: 'anisotropic' | 'uniform-baseline';
  /** Empty when usable as one piece; otherwise why not and what to do (flatten_problem, flatten.h). */
  problem: string;
  /**
   * What a usable pattern still should say (flatten_warnings, flatten.h): a mean shear above 5°, a direction
   * (nearly) along the normal on many triangles or filled from neighbours. Empty when nothing.
   */
  warnings: string[];
  /**
   * The edge-connected regions whose triangles miss the wanted stretch by more
   * than the core's threshold (kCutRegionError, flatten.h), largest first;
   * empty when none does.
   */
  suggestedCuts: SuggestedCut[];
}

/** All arrays are copies (JS-owned). */
export interface FlattenResult {
  /** #V*2 pattern coordinates (model units) per input vertex; NaN outside the patch. */
  uv: Float32Array;
  /** Patch triangles, 3 input-vertex indices each (#T*3). */
  triangles: Uint32Array;
  /** Per patch triangle: |along / su - 1|; NaN for a degenerate triangle. */
  compressionError: Float32Array;
  /** Per patch triangle: |across / sv - 1|; NaN for a degenerate triangle. */
  crossError: Float32Array;
  /** #V: area-weighted mean compression error of the vertex's patch triangles; NaN outside the patch. */
  vertexError: Float32Array;
  /** Per component: the grainline, a unit 2D vector in uv. */
  grainlines: Vec2[];
  /** Boundary loops (pattern outlines), input-vertex indices in walking order. */
  outlines: Uint32Array[];
  /** Per outline: the piece (component) it bounds, the index of its grainline. */
  outlinePieces: Int32Array;
  metrics: FlattenMetrics;
  /** Factorizations so far in this session (a repeated flatten of the same patch adds none). */
  factorizations: number;
}

/** @schema setMesh */
export interface SetMeshOptions {
  /** Merge vertices at equal positions (an unindexed three.js geometry); default false. A soup is welded anyway. */
  weld?: boolean;
}

/** @schema exportPattern */
export interface PatternOptions {
  /**
   * Millimetres per model unit. Default 1 here: the module does not guess. The page's API
   * (anisoform.exportPattern) and the CLI's flatten default to the guessed unit, info().unitGuess.mmPerUnit;
   * pass that to export as they do.
   */
  mmPerUnit?: number;
}

/** @schema document.mesh */
export interface DocumentMesh {
  /** The base mesh's file name (its extension gives the format). */
  name: string;
  vertices: number;
  triangles: number;
  /** Session.meshHash() of the mesh as loaded: 'fnv1a64:' and 16 hex digits. */
  hash: string;
}

/** @schema document.step */
export interface DocumentSelectStep {
  region: Region;
  /** As SelectOptions.falloff (default 0). */
  falloff?: number;
  /** As SelectOptions.mode (default 'replace'). */
  mode?: 'replace' | 'add' | 'subtract';
}

/** @schema document.region */
export interface DocumentRegion {
  /** Unique in the document; ops refer to it. */
  name: string;
  /** Run in order from an empty selection, on the rest pose the op starts from. Sparse weights: one `vertices` step. */
  steps: DocumentSelectStep[];
}

/** @schema document.op */
export interface DocumentOp {
  /** Unique in the document. */
  id: string;
  label?: string;
  /** default true; a disabled op is skipped by replay. */
  enabled?: boolean;
  /** A DocumentRegion's name. */
  region: string;
  /** Resolved and view-independent (Session.resolveOp): no screen drags, the twist origin and iterations as used. */
  op: DeformOp;
}

/** @schema document */
export interface EditDocument {
  format: 'anisoform-document';
  version: 1;
  mesh: DocumentMesh;
  regions: DocumentRegion[];
  ops: DocumentOp[];
}

/** @schema replay */
export interface ReplayOptions {
  /** First op to run (default 0: from the mesh as loaded; > 0: from the session's rest pose). */
  from?: number;
  /** One past the last op to run (default: all). */
  to?: number;
  /** Each op as a live preview (at most 4 iterations, cold): a quick look, never a commit (default false). */
  preview?: boolean;
}

export interface ReplaySummary {
  /** Enabled ops solved. */
  replayed: number;
  /** Disabled ops. */
  skipped: number;
  /**
   * Ops that left the mesh unchanged, and why: "document.ops[1] (id 'b'):
   * its region 'r' holds no vertex: the mesh is left unchanged".
   */
  warnings: string[];
  /** The last solve's result (null when no op ran). */
  last: DeformResult | null;
}

/** Session.surfaceAttributes. */
export interface SurfaceAttributes {
  /** An OBJ's texture coordinates per triangle corner: u, v of corners 0, 1, 2 (6 numbers a triangle). */
  cornerUv: Float32Array | null;
  /** Vertex colours in [0, 1], r, g, b per vertex: an OBJ's `v x y z r g b` or a PLY's red, green, blue. */
  colors: Float32Array | null;
  /** An OBJ's materials (usemtl): each run's name and first triangle, ascending. */
  materials: { name: string; first: number }[];
}

/** One editing session on the WASM heap. Call delete() when done. */
export interface Session {
  /** Replaces the mesh; the format comes from `name`'s extension (.obj .off .ply .stl). On failure the session keeps its mesh. */
  loadMesh(bytes: Uint8Array | ArrayBuffer | ArrayBufferView, name: string): MeshInfo;
  /** Replaces the mesh from flat arrays; `weld` merges vertices at equal positions. */
  setMesh(positions: Float32Array | Float64Array | number[], triangles: Uint32Array | number[], options?: SetMeshOptions): MeshInfo;
  /**
   * After setMesh: vertex i of its arrays is vertex map[i] of the mesh loaded (welding merges
   * vertices; else the identity). Empty after loadMesh. A copy.
   */
  inputVertexMap(): Uint32Array;
  /**
   * What the loaded file carried besides positions and triangles, for a GLB export (OBJ and PLY
   * exports carry it themselves): copies, null or empty where the file had none.
   */
  surfaceAttributes(): SurfaceAttributes;
  info(): MeshInfo;
  /** VIEW on the WASM heap (xyz per vertex): fetch again after every call, copy to keep. */
  positions(): Float32Array;
  /** VIEW on the WASM heap (3 indices per triangle). */
  triangles(): Uint32Array;
  /** Returns the number of vertices with weight > 0. Regions are evaluated on the rest pose. */
  select(region: Region, options?: SelectOptions): number;
  /** One weight in [0, 1] per vertex; returns the number with weight > 0. */
  setSelection(weights: Float32Array | number[]): number;
  /** VIEW on the WASM heap: one weight per vertex. */
  selection(): Float32Array;
  /**
   * Deforms FROM the rest pose with the current selection; positions() then shows the result.
   * An empty selection leaves the mesh unchanged (selected: 0), as the CLI.
   */
  deform(op: DeformOp): DeformResult;
  /** The current positions become the rest pose (the next edit starts here). */
  commit(): void;
  /** The current positions go back to the rest pose. */
  cancel(): void;
  /**
   * The rest pose's set-up for its next edit (the factorization first), one part per call: a host with
   * one thread calls it in the background after a load, a commit or a restore, and answers other
   * calls between the parts. Changes no edit state and no
   * result. Reports the stage 'factorize' with the share done (setProgress) and returns it: 1
   * when nothing is left (a call is then free).
   */
  prepareStep(): number;
  /** Restores positions (undo/redo); they also become the rest pose. */
  setPositions(positions: Float32Array | Float64Array | number[]): void;
  /** Unit tangent direction per vertex (#V*3, a copy), as the AnARAP solver frames it: for glyphs. */
  directionField(direction: Direction): Float32Array;
  /**
   * Per vertex (a copy): 'area' = one-ring area ratio; 'stretch' = the principal stretch farthest
   * from 1 by ratio (2 and 0.5 equally strong), area-weighted over the one-ring; 1 = unchanged.
   */
  distortion(kind: 'area' | 'stretch', reference?: 'rest' | 'loaded'): Float32Array;
  /** The current mesh as file bytes (a copy; PLY and STL binary). */
  exportMesh(format: 'obj' | 'off' | 'ply' | 'stl'): Uint8Array;
  /**
   * Flattens the CURRENT positions (what the user sees) into a garment pattern, as `anisoform
   * flatten`. The patch's factorization is kept while the positions and the patch are unchanged:
   * another compress/direction/baseline costs no factorization. A closed patch -> 'bad-mesh'; an
   * empty selection -> 'bad-parameter'; the session is then unchanged.
   */
  flatten(options?: FlattenOptions): FlattenResult;
  /**
   * The last flatten() as SVG or DXF text bytes in millimetres (a copy): one outline per boundary
   * loop, a grainline per piece, a scale bar. Any change of the positions (load, deform, cancel,
   * commit, setPositions) drops the last flattening: 'bad-parameter' "flatten first".
   */
  exportPattern(format: 'svg' | 'dxf', options?: PatternOptions): Uint8Array;
  /** Over the whole session: every rest pose and every flattened patch. */
  factorizations(): number;
  /**
   * The most vertices a mesh may have in this module: loadMesh/setMesh refuse a bigger one at once
   * with 'bad-mesh', naming both numbers (every edit factorizes the whole mesh: about 4 KB per
   * vertex, within the module's 2 GB).
   */
  vertexLimit(): number;
  /**
   * Progress of the long calls: `report(stage, fraction)` is called inside loadMesh/setMesh
   * ('load'), an edit's set-up of the rest pose ('factorize', on prepareStep's scale: 0.3 after
   * the unit copy and its Laplacian, 0.35 after the workspace, the factorization from 0.35 to
   * 0.95 (0.56 once ordered and analysed, then by twentieths of the numeric work), 1 after the
   * iterations' structures; the parts already done report nothing), deform's iterations ('solve': iterations
   * over the cap, then 1 when done) and flatten's ('flatten'). null stops it. It runs inside the
   * call: a Session call made from it (any session's; a new mesh or a delete would free memory the
   * running call uses) throws 'bad-parameter'. What `report` throws does not stop the call: the
   * call runs to its end, then throws it (its code kept, else 'bad-parameter').
   */
  setProgress(report: ((stage: 'load' | 'factorize' | 'solve' | 'flatten', fraction: number) => void) | null): void;
  /**
   * Replays an edit document (an object, or its JSON text) on this session's mesh: each enabled op's
   * region, a full cold solve, a commit. Deterministic (bitwise) for a build. The selection is then
   * cleared. Any error (bad JSON, version, region, amounts, a mesh whose hash differs) names the op
   * or field, and the session is left as it was.
   */
  replay(document: EditDocument | string, options?: ReplayOptions): ReplaySummary;
  /** Selects op `opId`'s region, evaluated on the rest pose; returns the number selected. */
  selectDocumentRegion(document: EditDocument | string, opId: string): number;
  /** The op as a document stores it: resolved on the rest pose and selection, a screen drag as its 3D vector. */
  resolveOp(op: DeformOp): DeformOp;
  /** The hash a document's mesh.hash must equal. */
  meshHash(): string;
  /** The current positions as the session's doubles (a copy): for bitwise comparisons and caches. */
  positionsExact(): Float64Array;
  delete(): void;
  isDeleted(): boolean;
}

export interface AnisoformWasm {
  Session: { new (): Session };
  /**
   * Bytes malloc'd now (inUse), of WASM memory (heap: it only grows, never shrinks) and the most
   * it may grow to (limit, 2 GB); beyond it a call fails with code 'out-of-memory'.
   */
  memoryUse(): { inUse: number; heap: number; limit: number };
  /** The keys the core accepts in each request object, by the `@schema` paths above. */
  opSchema(): Record<string, string[]>;
}

export interface CreateOptions {
  /** The .wasm bytes (Node: readFileSync of anisoform.wasm). */
  wasmBinary?: ArrayBuffer | Uint8Array;
  /** Where to find anisoform.wasm, as Emscripten's locateFile. */
  locateFile?: (path: string, prefix: string) => string;
}

export function createAnisoformWasm(options?: CreateOptions): Promise<AnisoformWasm>;
