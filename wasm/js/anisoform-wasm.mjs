// The JS layer over the Anisoform WASM module (wasm/bindings.cpp): loading,
// the public operation objects turned into the flat requests the bindings
// read, checks of the caller's input with messages that name the field, and
// every failure turned into an AnisoformError with a code.
//
// This file is copied next to anisoform.mjs / anisoform.wasm by the build
// (build dir and web/src/wasm/), and imports the module from beside itself.
//
// Memory: a Session lives on the WASM heap and must be delete()d. positions(),
// triangles() and selection() are views on that heap: any later call may grow
// the memory and detach them (length 0), so fetch them again after every call
// and copy (.slice()) what you keep.
import createAnisoformModule from './anisoform.mjs';

const ERROR_CODES = new Set(['bad-parameter', 'bad-mesh', 'bad-file', 'numerical', 'out-of-memory', 'internal']);

export class AnisoformError extends Error {
  constructor(code, message, options) {
    super(message, options);
    this.name = 'AnisoformError';
    this.code = code;
  }
}

// Defaults of a deform op, as the CLI's (iterations, tolerance) and METHOD.md's.
export const DEFAULTS = Object.freeze({
  method: 'anarap',
  maxIterations: 50,
  rotationSteps: 1,
  tolerance: 1e-6,
  curvatureSmoothing: 10,
  elements: 'spokes',
});

// Defaults of a flatten, as the CLI's `anisoform flatten` (ArapFlattenSettings).
export const FLATTEN_DEFAULTS = Object.freeze({
  compress: Object.freeze([1, 1]),
  patch: 'mesh',
  maxIterations: 500,
  tolerance: 1e-8,
});

// ---- errors ---------------------------------------------------------------

function toAnisoformError(error) {
  if (error instanceof AnisoformError) return error;
  if (error instanceof Error && ERROR_CODES.has(error.code)) {
    return new AnisoformError(error.code, error.message);
  }
  if (typeof error === 'number') {
    // A C++ exception that escaped the bindings' guard (TOOLCHAIN.md §1).
    return new AnisoformError('internal', `uncaught C++ exception (pointer ${error})`);
  }
  const message = error instanceof Error ? error.message : String(error);
  return new AnisoformError('internal', message, { cause: error });
}

// Runs a raw binding call. The bindings RETURN a failure as an Error with a
// code (throwing it from inside the module would leak module memory, see
// bindings.cpp); anything thrown is a failure of the module itself.
export function callModule(call) {
  let result;
  try {
    result = call();
  } catch (error) {
    throw toAnisoformError(error);
  }
  if (result instanceof Error) throw toAnisoformError(result);
  return result;
}

function badParameter(message) {
  return new AnisoformError('bad-parameter', message);
}

// ---- checks of the caller's values -----------------------------------------

function isObject(value) {
  return typeof value === 'object' && value !== null && !ArrayBuffer.isView(value) && !Array.isArray(value);
}

function requireObject(value, name) {
  if (!isObject(value)) throw badParameter(`${name} must be an object`);
  return value;
}

function rejectUnknownKeys(object, allowed, name) {
  for (const key of Object.keys(object)) {
    if (!allowed.includes(key)) {
      throw badParameter(`${name} has an unknown field '${key}' (allowed: ${allowed.join(', ')})`);
    }
  }
}

function finiteNumber(value, name) {
  if (typeof value !== 'number' || !Number.isFinite(value)) {
    throw badParameter(`${name} must be a finite number, got ${describe(value)}`);
  }
  return value;
}

function integerAtLeast(value, minimum, name) {
  if (!Number.isInteger(value) || value < minimum) {
    throw badParameter(`${name} must be an integer >= ${minimum}, got ${describe(value)}`);
  }
  return value;
}

function finiteVector(value, length, name) {
  const isArrayLike = Array.isArray(value) || (ArrayBuffer.isView(value) && !(value instanceof DataView));
  if (!isArrayLike || value.length !== length) {
    throw badParameter(`${name} must be ${length} finite numbers, got ${describe(value)}`);
  }
  const numbers = Array.from(value);
  numbers.forEach((x, i) => finiteNumber(x, `${name}[${i}]`));
  return numbers;
}

function nonZeroVector(value, name) {
  const v = finiteVector(value, 3, name);
  if (Math.hypot(...v) === 0) throw badParameter(`${name} must not be the zero vector`);
  return v;
}

function oneOf(value, choices, name) {
  if (!choices.includes(value)) {
    throw badParameter(`${name} must be one of ${choices.join(', ')}, got ${describe(value)}`);
  }
  return value;
}

// Each index is checked by the module before it is narrowed (js_values.h checked_indices).
function indexList(value, name) {
  if (value === undefined) return [];
  const isArrayLike = Array.isArray(value) || (ArrayBuffer.isView(value) && !(value instanceof DataView));
  if (!isArrayLike) throw badParameter(`${name} must be an array of vertex indices`);
  return value;
}

// Positions may come as float32 (GPU buffers) or float64 (exact, e.g. from
// cappedCylinder); the module reads both as doubles.
function positionArray(value, name) {
  if (value instanceof Float32Array || value instanceof Float64Array) return value;
  if (Array.isArray(value)) return Float64Array.from(value);
  throw badParameter(`${name} must be a Float32Array or Float64Array (or an array of numbers)`);
}

function typedArray(value, Type, name) {
  if (value instanceof Type) return value;
  if (Array.isArray(value)) return Type.from(value);
  throw badParameter(`${name} must be a ${Type.name} (or an array of numbers)`);
}

function describe(value) {
  if (typeof value === 'string') return `'${value}'`;
  if (Array.isArray(value)) return `an array of length ${value.length}`;
  if (ArrayBuffer.isView(value)) return `a ${value.constructor.name} of length ${value.length}`;
  if (isObject(value)) return 'an object';
  return String(value);
}

// ---- public objects -> the flat requests of bindings.cpp (js_values.h) -------

const REGION_KINDS = ['all', 'sphere', 'box', 'vertices'];

// region: {all: true} | {sphere: {center, radius}} | {box: {min, max}}
//         | {vertices: number[], weights?: number[]}
function normalizeRegion(region) {
  requireObject(region, 'region');
  const kinds = REGION_KINDS.filter((kind) => region[kind] !== undefined);
  if (kinds.length !== 1) {
    throw badParameter(`region must have exactly one of ${REGION_KINDS.join(', ')}; got ${kinds.join(', ') || 'none'}`);
  }
  const [kind] = kinds;
  rejectUnknownKeys(region, kind === 'vertices' ? ['vertices', 'weights'] : [kind], 'region');
  switch (kind) {
    case 'all':
      if (region.all !== true) throw badParameter('region.all must be true');
      return { kind: 'all' };
    case 'sphere': {
      const sphere = requireObject(region.sphere, 'region.sphere');
      rejectUnknownKeys(sphere, ['center', 'radius'], 'region.sphere');
      return {
        kind: 'sphere',
        center: finiteVector(sphere.center, 3, 'region.sphere.center'),
        radius: finiteNumber(sphere.radius, 'region.sphere.radius'),
      };
    }
    case 'box': {
      const box = requireObject(region.box, 'region.box');
      rejectUnknownKeys(box, ['min', 'max'], 'region.box');
      return { kind: 'box', min: finiteVector(box.min, 3, 'region.box.min'), max: finiteVector(box.max, 3, 'region.box.max') };
    }
    default: {
      const normalized = { kind: 'vertices', vertices: indexList(region.vertices, 'region.vertices') };
      if (region.weights !== undefined) {
        const weights = finiteVector(region.weights, normalized.vertices.length, 'region.weights');
        normalized.weights = weights;
      }
      return normalized;
    }
  }
}

// direction: {type:'global', vector} | {type:'curvature', which, smoothing?}
//   | {type:'screen', from, to, camera: {view, projection, viewport, anchor}}
//   | {type:'constraints', constraints: [{vertex, direction, su?, sv?}]}
//   | {type:'dense', directions: Float32Array (#V*3)}
function normalizeDirection(direction, name) {
  requireObject(direction, name);
  const type = oneOf(direction.type, ['global', 'curvature', 'screen', 'constraints', 'dense'], `${name}.type`);
  switch (type) {
    case 'global':
      rejectUnknownKeys(direction, ['type', 'vector'], name);
      return { kind: 'global', vector: nonZeroVector(direction.vector, `${name}.vector`) };
    case 'curvature': {
      rejectUnknownKeys(direction, ['type', 'which', 'smoothing'], name);
      const which = oneOf(direction.which, ['min', 'max'], `${name}.which`);
      const smoothing = direction.smoothing === undefined ? DEFAULTS.curvatureSmoothing
        : integerAtLeast(direction.smoothing, 0, `${name}.smoothing`);
      return { kind: `curvature-${which}`, smoothing };
    }
    case 'screen': {
      rejectUnknownKeys(direction, ['type', 'from', 'to', 'camera'], name);
      const camera = requireObject(direction.camera, `${name}.camera`);
      rejectUnknownKeys(camera, ['view', 'projection', 'viewport', 'anchor'], `${name}.camera`);
      return {
        kind: 'screen',
        screen: {
          from: finiteVector(direction.from, 2, `${name}.from`),
          to: finiteVector(direction.to, 2, `${name}.to`),
          view: finiteVector(camera.view, 16, `${name}.camera.view`),
          projection: finiteVector(camera.projection, 16, `${name}.camera.projection`),
          viewport: finiteVector(camera.viewport, 4, `${name}.camera.viewport`),
          anchor: finiteVector(camera.anchor, 3, `${name}.camera.anchor`),
        },
      };
    }
    case 'constraints': {
      rejectUnknownKeys(direction, ['type', 'constraints'], name);
      if (!Array.isArray(direction.constraints) || direction.constraints.length === 0) {
        throw badParameter(`${name}.constraints must be a non-empty array`);
      }
      return {
        kind: 'constraints',
        constraints: direction.constraints.map((c, i) => {
          const where = `${name}.constraints[${i}]`;
          requireObject(c, where);
          rejectUnknownKeys(c, ['vertex', 'direction', 'su', 'sv'], where);
          const hasAmounts = c.su !== undefined || c.sv !== undefined;
          return {
            vertex: integerAtLeast(c.vertex, 0, `${where}.vertex`),
            direction: nonZeroVector(c.direction, `${where}.direction`),
            hasAmounts,
            su: c.su === undefined ? 1 : finiteNumber(c.su, `${where}.su`),
            sv: c.sv === undefined ? 1 : finiteNumber(c.sv, `${where}.sv`),
          };
        }),
      };
    }
    case 'dense':
      rejectUnknownKeys(direction, ['type', 'directions'], name);
      return { kind: 'dense', dense: typedArray(direction.directions, Float32Array, `${name}.directions`) };
  }
  throw badParameter(`${name}.type is not handled`);
}

// transform: {scale?: su | [su] | [su, sv], thickness?: sn, shear?: h,
//             rotate?: {axis: 'n'|'u'|'v', degrees},
//             twist?: {axis: [x,y,z], degreesPerUnit, origin?: [x,y,z]}}
function normalizeTransform(transform) {
  const t = transform === undefined ? {} : requireObject(transform, 'op.transform');
  rejectUnknownKeys(t, ['scale', 'thickness', 'shear', 'rotate', 'twist'], 'op.transform');
  const out = { su: 1, sv: 1, sn: 1, shear: 0, rotateAxis: 'none', rotateDegrees: 0, twist: false };
  if (t.scale !== undefined) {
    if (typeof t.scale === 'number') {
      out.su = finiteNumber(t.scale, 'op.transform.scale');
    } else {
      const isPair = Array.isArray(t.scale) && (t.scale.length === 1 || t.scale.length === 2);
      if (!isPair) throw badParameter(`op.transform.scale must be su or [su, sv], got ${describe(t.scale)}`);
      out.su = finiteNumber(t.scale[0], 'op.transform.scale[0]');
      if (t.scale.length === 2) out.sv = finiteNumber(t.scale[1], 'op.transform.scale[1]');
    }
  }
  if (t.thickness !== undefined) out.sn = finiteNumber(t.thickness, 'op.transform.thickness');
  if (t.shear !== undefined) out.shear = finiteNumber(t.shear, 'op.transform.shear');
  if (t.rotate !== undefined) {
    const rotate = requireObject(t.rotate, 'op.transform.rotate');
    rejectUnknownKeys(rotate, ['axis', 'degrees'], 'op.transform.rotate');
    out.rotateAxis = oneOf(rotate.axis, ['n', 'u', 'v'], 'op.transform.rotate.axis');
    out.rotateDegrees = finiteNumber(rotate.degrees, 'op.transform.rotate.degrees');
  }
  if (t.twist !== undefined) {
    const twist = requireObject(t.twist, 'op.transform.twist');
    rejectUnknownKeys(twist, ['axis', 'degreesPerUnit', 'origin'], 'op.transform.twist');
    const axis = nonZeroVector(twist.axis, 'op.transform.twist.axis');
    const length = Math.hypot(...axis);
    out.twist = true;
    out.twistAxis = axis.map((x) => x / length);
    out.twistDegreesPerUnit = finiteNumber(twist.degreesPerUnit, 'op.transform.twist.degreesPerUnit');
    if (twist.origin !== undefined) out.twistOrigin = finiteVector(twist.origin, 3, 'op.transform.twist.origin');
  }
  return out;
}

const OP_KEYS = ['method', 'direction', 'transform', 'pins', 'handles', 'move', 'elements',
  'maxIterations', 'rotationSteps', 'tolerance', 'preview', 'warmStart'];

function normalizeOp(op, defaultDirection) {
  requireObject(op, 'op');
  rejectUnknownKeys(op, OP_KEYS, 'op');
  const optionalFlag = (value, fallback, name) => {
    if (value === undefined) return fallback;
    if (typeof value !== 'boolean') throw badParameter(`${name} must be true or false`);
    return value;
  };
  return {
    method: oneOf(op.method ?? DEFAULTS.method, ['anarap', 'andefgrad', 'arap', 'linear'], 'op.method'),
    direction: op.direction === undefined ? defaultDirection() : normalizeDirection(op.direction, 'op.direction'),
    transform: normalizeTransform(op.transform),
    pins: indexList(op.pins, 'op.pins'),
    handles: indexList(op.handles, 'op.handles'),
    move: op.move === undefined ? [0, 0, 0] : finiteVector(op.move, 3, 'op.move'),
    elements: oneOf(op.elements ?? DEFAULTS.elements, ['spokes', 'spokes-rims'], 'op.elements'),
    maxIterations: op.maxIterations === undefined ? DEFAULTS.maxIterations
      : integerAtLeast(op.maxIterations, 1, 'op.maxIterations'),
    rotationSteps: op.rotationSteps === undefined ? DEFAULTS.rotationSteps
      : integerAtLeast(op.rotationSteps, 1, 'op.rotationSteps'),
    tolerance: op.tolerance === undefined ? DEFAULTS.tolerance : finiteNumber(op.tolerance, 'op.tolerance'),
    preview: optionalFlag(op.preview, false, 'op.preview'),
    warmStart: optionalFlag(op.warmStart, true, 'op.warmStart'),
  };
}

// The CLI's default direction: the longest side of the bounding box (x on ties).
function longestAxisDirection(info) {
  return longestAxisOfBox(info.bbox.min, info.bbox.max);
}

function longestAxisOfBox(min, max) {
  const extent = max.map((x, k) => x - min[k]);
  let axis = 0;
  for (let k = 1; k < 3; ++k) if (extent[k] > extent[axis]) axis = k;
  const vector = [0, 0, 0];
  vector[axis] = 1;
  return { kind: 'global', vector };
}

// The same of the current positions (xyz per vertex): flatten works on what
// the user sees, which an edit may have moved away from info().bbox.
function longestAxisOfPositions(xyz) {
  const min = [Infinity, Infinity, Infinity];
  const max = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < xyz.length; i += 3) {
    for (let k = 0; k < 3; ++k) {
      min[k] = Math.min(min[k], xyz[i + k]);
      max[k] = Math.max(max[k], xyz[i + k]);
    }
  }
  return longestAxisOfBox(min, max);
}

const FLATTEN_KEYS = ['compress', 'direction', 'baseline', 'patch', 'maxIterations', 'tolerance'];

// options: {compress?: su | [su] | [su, sv], direction?: {type:'global', vector}
//           | {type:'constraints', constraints}, baseline?: 'uniform',
//           patch?: 'mesh'|'selection', maxIterations?, tolerance?}
// -> the request of js_values.h flatten_from_js.
function normalizeFlatten(options, defaultDirection) {
  const name = 'flatten: options';
  requireObject(options, name);
  rejectUnknownKeys(options, FLATTEN_KEYS, name);
  const positive = (value, field) => {
    finiteNumber(value, field);
    if (!(value > 0)) throw badParameter(`${field} must be > 0, got ${describe(value)}`);
    return value;
  };
  let [su, sv] = FLATTEN_DEFAULTS.compress;
  const { compress } = options;
  if (typeof compress === 'number') {
    su = positive(compress, `${name}.compress`);
  } else if (compress !== undefined) {
    const isPair = Array.isArray(compress) && (compress.length === 1 || compress.length === 2);
    if (!isPair) throw badParameter(`${name}.compress must be su, [su] or [su, sv], got ${describe(compress)}`);
    su = positive(compress[0], `${name}.compress[0]`);
    if (compress.length === 2) sv = positive(compress[1], `${name}.compress[1]`);
  }
  let direction;
  if (options.direction === undefined) {
    direction = defaultDirection();
  } else {
    requireObject(options.direction, `${name}.direction`);
    oneOf(options.direction.type, ['global', 'constraints'], `${name}.direction.type`);
    direction = normalizeDirection(options.direction, `${name}.direction`);
  }
  const method = options.baseline === undefined ? 'anisotropic'
    : (oneOf(options.baseline, ['uniform'], `${name}.baseline`), 'uniform-baseline');
  const patch = oneOf(options.patch ?? FLATTEN_DEFAULTS.patch, ['mesh', 'selection'], `${name}.patch`);
  const maxIterations = options.maxIterations === undefined ? FLATTEN_DEFAULTS.maxIterations
    : integerAtLeast(options.maxIterations, 1, `${name}.maxIterations`);
  let tolerance = FLATTEN_DEFAULTS.tolerance;
  if (options.tolerance !== undefined) {
    tolerance = finiteNumber(options.tolerance, `${name}.tolerance`);
    if (tolerance < 0) throw badParameter(`${name}.tolerance must be >= 0, got ${describe(tolerance)}`);
  }
  return { useSelection: patch === 'selection', su, sv, direction, method, maxIterations, tolerance };
}

function toBytes(bytes) {
  if (bytes instanceof Uint8Array) return bytes;
  if (bytes instanceof ArrayBuffer) return new Uint8Array(bytes);
  if (ArrayBuffer.isView(bytes)) return new Uint8Array(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  throw badParameter('loadMesh: bytes must be a Uint8Array or an ArrayBuffer');
}

// ---- the module -----------------------------------------------------------

// options: {wasmBinary?: ArrayBuffer|Uint8Array, locateFile?: (path, prefix) => string}
// (Node: pass wasmBinary, TOOLCHAIN.md §6; browsers and bundlers need neither.)
export async function createAnisoformWasm(options = {}) {
  return (await instantiateAnisoform(createAnisoformModule, options)).api;
}

// The API over a module built from wasm/bindings.cpp by `factory` (this
// module's, or the benchmarks' build, anisoform-bench-wasm.mjs): {api, module,
// rawSession(session) -> its embind object}.
export async function instantiateAnisoform(factory, options = {}) {
  const { wasmBinary, locateFile } = requireObject(options, 'options');
  const moduleOptions = {};
  if (wasmBinary !== undefined) moduleOptions.wasmBinary = wasmBinary;
  if (locateFile !== undefined) moduleOptions.locateFile = locateFile;
  let module;
  try {
    module = await factory(moduleOptions);
  } catch (error) {
    throw new AnisoformError('internal', `cannot load the WASM module: ${error?.message ?? error}`, { cause: error });
  }

  // Session wrapper -> its embind object, for the benchmarks' LaplacianFloor.
  const rawSessions = new WeakMap();

  class Session {
    #raw;

    constructor() {
      this.#raw = callModule(() => new module.Session());
      rawSessions.set(this, this.#raw);
    }

    get #session() {
      if (this.#raw === null) throw badParameter('this Session has been deleted');
      return this.#raw;
    }

    // Frees the WASM memory; the object is unusable afterwards.
    delete() {
      if (this.#raw !== null) {
        this.#raw.delete();
        this.#raw = null;
      }
    }

    isDeleted() {
      return this.#raw === null;
    }

    loadMesh(bytes, name) {
      if (typeof name !== 'string') throw badParameter('loadMesh: name must be a string (its extension gives the format)');
      const data = toBytes(bytes);
      return callModule(() => this.#session.loadMesh(data, name));
    }

    setMesh(positions, triangles, options = {}) {
      const { weld = false } = requireObject(options, 'setMesh options');
      const xyz = positionArray(positions, 'setMesh: positions');
      const indices = indexList(triangles, 'setMesh: triangles');
      if (typeof weld !== 'boolean') throw badParameter('setMesh: options.weld must be true or false');
      return callModule(() => this.#session.setMesh(xyz, indices, weld));
    }

    info() {
      return callModule(() => this.#session.info());
    }

    positions() {
      return callModule(() => this.#session.positions());
    }

    triangles() {
      return callModule(() => this.#session.triangles());
    }

    select(region, options = {}) {
      requireObject(options, 'select options');
      rejectUnknownKeys(options, ['falloff', 'mode'], 'select options');
      const normalized = normalizeRegion(region);
      const falloff = options.falloff === undefined ? 0 : finiteNumber(options.falloff, 'select: options.falloff');
      const mode = oneOf(options.mode ?? 'replace', ['replace', 'add', 'subtract'], 'select: options.mode');
      return callModule(() => this.#session.select(normalized, falloff, mode));
    }

    setSelection(weights) {
      const values = typedArray(weights, Float32Array, 'setSelection: weights');
      return callModule(() => this.#session.setSelection(values));
    }

    selection() {
      return callModule(() => this.#session.selection());
    }

    deform(op) {
      const request = normalizeOp(op, () => longestAxisDirection(this.info()));
      return callModule(() => this.#session.deform(request));
    }

    commit() {
      callModule(() => this.#session.commit());
    }

    cancel() {
      callModule(() => this.#session.cancel());
    }

    setPositions(positions) {
      const xyz = positionArray(positions, 'setPositions: positions');
      callModule(() => this.#session.setPositions(xyz));
    }

    directionField(direction) {
      const normalized = normalizeDirection(direction, 'direction');
      return callModule(() => this.#session.directionField(normalized));
    }

    distortion(kind, reference = 'rest') {
      oneOf(kind, ['area', 'stretch'], 'distortion: kind');
      oneOf(reference, ['rest', 'loaded'], 'distortion: reference');
      return callModule(() => this.#session.distortion(kind, reference));
    }

    exportMesh(format) {
      oneOf(format, ['obj', 'off', 'ply', 'stl'], 'exportMesh: format');
      return callModule(() => this.#session.exportMesh(format));
    }

    // A garment pattern of the current positions (the whole mesh or the
    // selected patch); see CONTRACT.md for the options and the result.
    flatten(options = {}) {
      const request = normalizeFlatten(options, () => longestAxisOfPositions(this.positions()));
      return callModule(() => this.#session.flatten(request));
    }

    // The last flatten() as SVG or DXF text bytes, in millimetres.
    exportPattern(format, options = {}) {
      oneOf(format, ['svg', 'dxf'], 'exportPattern: format');
      requireObject(options, 'exportPattern options');
      rejectUnknownKeys(options, ['mmPerUnit'], 'exportPattern options');
      const mmPerUnit = options.mmPerUnit === undefined ? 1 : finiteNumber(options.mmPerUnit, 'exportPattern: options.mmPerUnit');
      if (!(mmPerUnit > 0)) throw badParameter(`exportPattern: options.mmPerUnit must be > 0, got ${mmPerUnit}`);
      return callModule(() => this.#session.exportPattern(format, mmPerUnit));
    }

    factorizations() {
      return callModule(() => this.#session.factorizations());
    }
  }

  // {inUse, heap, limit} in bytes: malloc'd now, the WASM memory (it never shrinks), its maximum.
  const memoryUse = () => callModule(() => module.memoryUse());

  return { api: { Session, memoryUse }, module, rawSession: (session) => rawSessions.get(session) };
}
