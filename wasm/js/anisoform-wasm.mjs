// The JS layer over the Anisoform WASM module (wasm/bindings.cpp): loading,
// argument conversion and error mapping, nothing else. The requests (ops,
// regions, directions, flatten options) go to the core as JSON, where their
// one schema, defaults and checks live (core/include/anisoform/op.h); every
// failure comes back as an AnisoformError with a code. Types and contract:
// anisoform-wasm.d.ts beside this file.
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

function badParameter(message) {
  return new AnisoformError('bad-parameter', message);
}

function toAnisoformError(error) {
  if (error instanceof AnisoformError) return error;
  if (error instanceof Error && ERROR_CODES.has(error.code)) return new AnisoformError(error.code, error.message);
  // embind refusing an argument of the wrong type ("Cannot pass non-string to std::string").
  if (error?.name === 'BindingError') return new AnisoformError('bad-parameter', error.message, { cause: error });
  if (typeof error === 'number') {
    // A C++ exception that escaped the bindings' guard (TOOLCHAIN.md §1).
    return new AnisoformError('internal', `uncaught C++ exception (pointer ${error})`);
  }
  const message = error instanceof Error ? error.message : String(error);
  return new AnisoformError('internal', message, { cause: error });
}

// Runs a raw binding call. The bindings RETURN a failure as an Error with a
// code (throwing it from inside the module would leak module memory, see
// wasm/guarded.h); anything thrown is a failure of the module itself.
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

// ---- argument conversion ----------------------------------------------------

const isTypedArray = (value) => ArrayBuffer.isView(value) && !(value instanceof DataView);

// A request as the JSON text the core parses: typed arrays become arrays, and
// the numbers JSON cannot hold become the strings "NaN", "Infinity" and
// "-Infinity", which the core refuses naming the field (JSON.stringify would
// turn them into null). `undefined` is sent as null, which the core refuses
// where a value is required.
function toJson(value, what) {
  try {
    return JSON.stringify(value === undefined ? null : value, (key, item) => {
      if (typeof item === 'number' && !Number.isFinite(item)) return String(item);
      return isTypedArray(item) ? Array.from(item) : item;
    });
  } catch (error) {
    throw badParameter(`${what} cannot be sent as JSON: ${error.message}`);
  }
}

// Bulk arrays go to the module as they are; a plain array becomes a typed one.
const describe = (value) => (value === undefined ? 'missing' : typeof value === 'string' ? JSON.stringify(value) : String(value));
const isBigIntArray = (value) => value instanceof BigInt64Array || value instanceof BigUint64Array;

function numbers(value, Type, what) {
  if (isBigIntArray(value)) throw badParameter(`${what} must hold numbers, not BigInts (a ${value.constructor.name})`);
  if (isTypedArray(value)) return value;
  if (Array.isArray(value)) {
    // Type.from would read '1' as 1, null as 0 and a hole as NaN.
    for (let i = 0; i < value.length; i++) {
      if (typeof value[i] !== 'number') throw badParameter(`${what}[${i}] is ${describe(value[i])}, not a number`);
    }
    return Type.from(value);
  }
  throw badParameter(`${what} must be a typed array or an array of numbers`);
}

const documentText = (document) => (typeof document === 'string' ? document : toJson(document, 'document'));

function bytesOf(bytes) {
  if (bytes instanceof Uint8Array) return bytes;
  if (bytes instanceof ArrayBuffer) return new Uint8Array(bytes);
  if (ArrayBuffer.isView(bytes)) return new Uint8Array(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  throw badParameter('loadMesh: bytes must be a Uint8Array or an ArrayBuffer');
}

// ---- the module -------------------------------------------------------------

// options: {wasmBinary?: ArrayBuffer|Uint8Array, locateFile?: (path, prefix) => string}
// (Node: pass wasmBinary, TOOLCHAIN.md §6; browsers and bundlers need neither.)
export async function createAnisoformWasm(options = {}) {
  return (await instantiateAnisoform(createAnisoformModule, options)).api;
}

// The API over a module built from wasm/bindings.cpp by `factory` (this
// module's, or the benchmarks' build, anisoform-bench-wasm.mjs): {api, module,
// rawSession(session) -> its embind object}.
export async function instantiateAnisoform(factory, options = {}) {
  if (typeof options !== 'object' || options === null) throw badParameter('options must be an object');
  const { wasmBinary, locateFile } = options;
  let module;
  try {
    module = await factory({ ...(wasmBinary && { wasmBinary }), ...(locateFile && { locateFile }) });
  } catch (error) {
    throw new AnisoformError('internal', `cannot load the WASM module: ${error?.message ?? error}`, { cause: error });
  }
  const rawSessions = new WeakMap();
  // The Session call running now: a progress report runs inside it, and a
  // call from there (a new mesh, a delete) freed memory the running solve
  // still used; the module's memory was corrupt from then on, for every session.
  let running = null;
  const refuseInside = (method) => {
    if (running) {
      throw badParameter(`Session.${method}() was called while Session.${running}() runs (from its progress report): `
        + `call it after ${running}() has returned`);
    }
  };

  class Session {
    #raw;
    // What the progress report threw during the running call: kept, not let
    // through the core's frames (which then never unwind), and thrown once
    // the call has returned.
    #reportError = null;

    constructor() {
      this.#raw = callModule(() => new module.Session());
      rawSessions.set(this, this.#raw);
    }

    #call(method, ...args) {
      if (this.#raw === null) throw badParameter('this Session has been deleted');
      refuseInside(method);
      running = method;
      this.#reportError = null;
      let result;
      try {
        result = callModule(() => this.#raw[method](...args));
      } catch (error) {
        // embind's own refusal of an argument ("Cannot pass non-string to std::string") names no call.
        if (error.cause?.name !== 'BindingError') throw error;
        throw new AnisoformError('bad-parameter', `Session.${method}(): an argument has the wrong type: ${error.message}`, { cause: error.cause });
      } finally {
        running = null;
      }
      const thrown = this.#reportError;
      if (thrown === null) return result;
      this.#reportError = null;
      const code = thrown instanceof AnisoformError ? thrown.code : 'bad-parameter';
      throw new AnisoformError(code, `Session.${method}() has run to its end, but its progress report threw: ${thrown?.message ?? thrown}`,
        { cause: thrown });
    }

    // Frees the WASM memory; the object is unusable afterwards.
    delete() {
      refuseInside('delete');
      this.#raw?.delete();
      this.#raw = null;
    }

    isDeleted() {
      return this.#raw === null;
    }

    loadMesh(bytes, name) {
      if (typeof name !== 'string') throw badParameter('loadMesh: name must be a string (its extension gives the format)');
      return this.#call('loadMesh', bytesOf(bytes), name);
    }

    setMesh(positions, triangles, options = {}) {
      if (isBigIntArray(triangles)) throw badParameter(`setMesh: triangles must hold numbers, not BigInts (a ${triangles.constructor.name})`);
      return this.#call('setMesh', numbers(positions, Float64Array, 'setMesh: positions'), triangles,
        toJson(options, 'setMesh options'));
    }

    inputVertexMap() { return this.#call('inputVertexMap'); }

    surfaceAttributes() { return this.#call('surfaceAttributes'); }

    info() { return this.#call('info'); }

    positions() { return this.#call('positions'); }

    triangles() { return this.#call('triangles'); }

    select(region, options = {}) {
      return this.#call('select', toJson(region, 'region'), toJson(options, 'select options'));
    }

    setSelection(weights) {
      return this.#call('setSelection', numbers(weights, Float32Array, 'setSelection: weights'));
    }

    selection() { return this.#call('selection'); }

    deform(op) { return this.#call('deform', toJson(op, 'op')); }

    commit() { this.#call('commit'); }

    cancel() { this.#call('cancel'); }

    prepareStep() { return this.#call('prepareStep'); }

    setPositions(positions) {
      this.#call('setPositions', numbers(positions, Float64Array, 'setPositions: positions'));
    }

    directionField(direction) { return this.#call('directionField', toJson(direction, 'direction')); }

    distortion(kind, reference = 'rest') { return this.#call('distortion', kind, reference); }

    exportMesh(format) { return this.#call('exportMesh', format); }

    // A garment pattern of the current positions (the whole mesh or the
    // selected patch); the options and the result: anisoform-wasm.d.ts.
    flatten(options = {}) { return this.#call('flatten', toJson(options, 'flatten options')); }

    // The last flatten() as SVG or DXF text bytes, in millimetres.
    exportPattern(format, options = {}) {
      return this.#call('exportPattern', format, toJson(options, 'exportPattern options'));
    }

    factorizations() { return this.#call('factorizations'); }

    // The most vertices a mesh may have to load here (the module's memory
    // ceiling over the memory an edit needs per vertex); a bigger one is refused.
    vertexLimit() { return this.#call('vertexLimit'); }

    // report(stage, fraction) during loadMesh/setMesh ('load'), an edit's
    // set-up ('factorize', on prepareStep's scale), deform's iterations ('solve') and
    // flatten's ('flatten'); null stops it. It runs inside the call.
    setProgress(report) {
      if (report !== null && typeof report !== 'function') throw badParameter('setProgress: report must be a function or null');
      const kept = report && ((stage, fraction) => {
        try {
          report(stage, fraction);
        } catch (error) {
          this.#reportError ??= error;
        }
      });
      return this.#call('setProgress', kept);
    }

    // The edit document (core document.h): JSON text as it is, an object as JSON.
    replay(document, options = {}) {
      return this.#call('replay', documentText(document), toJson(options, 'replay options'));
    }

    selectDocumentRegion(document, opId) { return this.#call('selectDocumentRegion', documentText(document), opId); }

    resolveOp(op) { return this.#call('resolveOp', toJson(op, 'op')); }

    meshHash() { return this.#call('meshHash'); }

    positionsExact() { return this.#call('positionsExact'); }
  }

  // {inUse, heap, limit} in bytes: malloc'd now, the WASM memory (it never shrinks), its maximum.
  const memoryUse = () => callModule(() => module.memoryUse());

  // {PATH: [key...]}: what the core accepts in each request object (anisoform-wasm.d.ts `@schema`).
  const opSchema = () => callModule(() => module.opSchema());

  return { api: { Session, memoryUse, opSchema }, module, rawSession: (session) => rawSessions.get(session) };
}
