// The solver worker: hosts the WASM session off the main thread, so the page
// keeps drawing and answering input while a solve runs. Requests are handled
// one at a time, in order (see protocol.js).
import { createAnisoformWasm } from '../wasm/anisoform-wasm.mjs';
import { PROGRESS, Request } from './protocol.js';
import { SessionHost } from './session-host.js';
import { urlProblem } from '../shared/url-problem.js';

let host = null;
/** The WASM module, instantiated once: a worker kept in a SolverPool serves modeller after modeller. */
let wasm = null;

function reportProgress(stage, message, fraction) {
  self.postMessage({ kind: PROGRESS, stage, message, fraction });
}

// Each init starts a new session: the first loads the WASM, a later one (a
// worker handed to another modeller by a SolverPool) frees the last
// modeller's session and reuses the module.
async function initialize({ wasmUrl }) {
  reportProgress('init', 'Loading the solver');
  host?.dispose();
  host = null;
  // wasmUrl: the embedder's override (SolverClient); by default the loader
  // finds the WASM beside itself. A pool hands a worker only to a modeller
  // with the same URLs.
  try {
    wasm ??= await createAnisoformWasm(
      wasmUrl === undefined ? {} : { locateFile: (path) => (path.endsWith('.wasm') ? wasmUrl : path) },
    );
  } catch (error) {
    // The compiler's "expected magic word" names neither the file nor why: the URL is asked.
    const problem = wasmUrl === undefined ? null : await urlProblem(wasmUrl, { wasm: true });
    if (problem) throw Object.assign(new Error(`cannot load the WASM module from ${wasmUrl}: ${problem}`), { code: 'bad-parameter' });
    throw error;
  }
  host = new SessionHost(wasm, reportProgress);
  return { result: {}, transfer: [] };
}

// Errors become {code, message}: AnisoformError carries the core's code;
// anything else is an internal error, reported with its message.
function describeError(error) {
  if (error && typeof error === 'object') {
    return { code: error.code ?? 'internal', message: error.message ?? String(error) };
  }
  return { code: 'internal', message: String(error) };
}

// Module workers may receive messages while `initialize` awaits; chaining
// every request on one promise keeps them in order.
let queue = Promise.resolve();

self.onmessage = (event) => {
  const { id, kind, ...payload } = event.data;
  queue = queue.then(async () => {
    try {
      const { result, transfer } =
        kind === Request.init ? await initialize(payload) : await requireHost().handle(kind, payload);
      self.postMessage({ id, ok: true, result }, transfer);
    } catch (error) {
      self.postMessage({ id, ok: false, error: describeError(error) });
    }
  });
};

function requireHost() {
  if (!host) throw new Error('the solver is not initialized');
  return host;
}
