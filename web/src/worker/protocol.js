// The typed message protocol between the page and the solver worker.
//
// Every request is `{id, kind, ...payload}` (so no payload field may be named
// id or kind) and gets exactly one reply
// `{id, ok: true, result}` or `{id, ok: false, error: {code, message}}`.
// Between them the worker may post `{kind: 'progress', stage, message}`.
// The worker handles requests strictly in order; the client (solver-client.js)
// coalesces preview requests so the queue never holds a stale one.
// Typed arrays travel as transferables: the sender gives them up.

export const Request = Object.freeze({
  /** {wasmUrl?} -> {version}: load the WASM module (from wasmUrl if given) and create the session. */
  init: 'init',
  /**
   * {source: Blob | ArrayBuffer, name} -> MeshPayload & {sourceBytes: Blob}: core readers (OBJ,
   * OFF, PLY, STL). A Blob (a picked File) is read here, in the worker; sourceBytes is the
   * file's bytes as a Blob, kept for the autosave.
   */
  loadFile: 'loadFile',
  /**
   * {positions: Float32Array, triangles: Uint32Array, weld, display = true} -> MeshPayload &
   * {inputVertexMap?: Uint32Array} (GLB; a restart's seed, with display false: no normals or bvh,
   * the page shows that mesh already). inputVertexMap (with weld): Session.inputVertexMap.
   */
  setMesh: 'setMesh',
  /**
   * {} -> {share}: one part of the rest pose's set-up for its next edit (Session.prepareStep: the
   * factorization first), so that the first drag is live; share is how much is done, 1 when all.
   * The page asks for the next part once this one is back, so what it asks meanwhile (a select)
   * runs between the parts, not after the whole set-up.
   */
  prepareStep: 'prepareStep',
  /**
   * {triangles: number} -> {vertices: Uint32Array, triangles: Uint32Array}:
   * the rest mesh simplified to about that many triangles, over a subset of
   * its vertices (display-proxy.js), for the page to draw while it moves.
   */
  simplify: 'simplify',
  /**
   * {region, options: {falloff, mode}} -> {count, weights: Float32Array}: the
   * core's selection rule (Session.select) on the rest pose; weights is a copy
   * of the session's whole selection afterwards.
   */
  select: 'select',
  /** {weights: Float32Array} -> {count}. */
  setSelection: 'setSelection',
  /**
   * {op, commit, distortion?: 'area'|'stretch'} -> {positions, stats, distortion?}:
   * a preview (commit false) or a committed edit; with `distortion`, the
   * reply also carries that distortion against the mesh as loaded
   * (Session.distortion, a ratio per vertex) for the heat map.
   */
  deform: 'deform',
  /** {distortion: 'area'|'stretch'} -> {values: Float32Array}: Session.distortion(distortion, 'loaded'). */
  distortion: 'distortion',
  /** {} -> {positions}: drop the preview, back to the rest mesh. */
  cancel: 'cancel',
  /** {positions} -> {}: undo/redo/reset; the positions become the rest mesh. */
  setPositions: 'setPositions',
  /** {direction} -> {field: Float32Array}: per-vertex unit directions for glyphs. */
  directionField: 'directionField',
  /** {format: 'obj'|'off'|'ply'|'stl'} -> {bytes: Uint8Array}: the current positions as a mesh file (the core's writers). */
  exportMesh: 'exportMesh',
  /** {} -> Session.surfaceAttributes (the file's texture, colours, materials): for a GLB export by the page. */
  surfaceAttributes: 'surfaceAttributes',
  /** {options} -> FlattenPayload: a garment pattern of the current positions. */
  flatten: 'flatten',
  /** {format: 'svg'|'dxf', mmPerUnit} -> {bytes: Uint8Array}: the last flattening as a pattern file. */
  exportPattern: 'exportPattern',
  /** {op} -> {op}: the op as the edit document stores it (Session.resolveOp: on the rest pose and selection). */
  resolveOp: 'resolveOp',
  /**
   * {document, from, to, preview?, distortion?, label?} -> {positions, exact: Float64Array, summary, distortion?}:
   * Session.replay of ops [from, to) (from > 0: from the session's rest pose; preview: each op as a
   * live preview, a slider on an earlier op); the result is the rest pose. `label` begins its
   * progress messages ("Edit 2 of 3: Solving").
   */
  replay: 'replay',
  /**
   * {document, opId} -> {count, weights: Float32Array}: Session.selectDocumentRegion on the rest
   * pose (a live re-parameterisation's selection; an op's region shown on the mesh).
   */
  selectDocumentRegion: 'selectDocumentRegion',
});

// Worker -> page, between requests' answers: {kind: PROGRESS, stage, message,
// fraction?}, fraction in [0, 1] when the core can tell (session-host.js).
export const PROGRESS = 'progress';

/**
 * @typedef {object} MeshInfo
 * @property {number} vertices
 * @property {number} triangles
 * @property {number} components
 * @property {number} boundaryLoops
 * @property {boolean} edgeManifold
 * @property {number} degenerateTriangles
 * @property {{kind: string, element: number, message: string}[]} problems
 * @property {string[]} notes
 */

/**
 * @typedef {object} MeshPayload
 * @property {MeshInfo} info
 * @property {Float32Array} positions   xyz per vertex
 * @property {Uint32Array} triangles    three vertex indices per triangle
 * @property {Float64Array} exact       the session's positions as doubles (the edit document's state 0)
 * @property {string} hash              Session.meshHash(): the edit document's mesh.hash
 * @property {Float32Array} [normals]   vertex normals of `positions` (worker/mesh-display.js)
 * @property {object} [bvh]             the picking BVH over `positions` and `triangles`:
 *                                      MeshBVH.serialize's {version, roots, indirectBuffer}
 */

/**
 * @typedef {object} DeformStats
 * @property {number} iterations
 * @property {number} energy
 * @property {number} ms           solver time reported by the core
 * @property {number} factorizations
 * @property {boolean} converged
 * @property {number} directionsFilled
 * @property {number} inverted      triangles folded over
 */

/**
 * @typedef {object} FlattenPayload  (wasm/CONTRACT.md, Session.flatten)
 * @property {Float32Array} uv                 u, v per mesh vertex; NaN outside the patch
 * @property {Uint32Array} triangles           the patch's triangles (mesh vertex indices)
 * @property {Float32Array} compressionError   per patch triangle |along/su - 1|
 * @property {Float32Array} crossError         per patch triangle |across/sv - 1|
 * @property {Float32Array} vertexError        per mesh vertex; NaN outside the patch
 * @property {number[][]} grainlines           per piece, a unit 2D vector
 * @property {Uint32Array[]} outlines          boundary loops (mesh vertex indices)
 * @property {Int32Array} outlinePieces        per outline, its piece (grainline index)
 * @property {object} metrics
 */
