// node bench/wasm-bench.mjs --mesh cyl1k|cyl10k|cyl50k|cyl200k|PATH [--runs N]
//                           [--iterations N] [--only IMPL,...] [--verbose]
//
// The native anisoform_bench's problems and timings (bench/problems.cpp,
// bench/impls.cpp, bench/main.cpp), run on the WASM module in Node, with the
// same JSON lines on stdout:
//   {"mesh":..., "vertices":..., "impl":..., "precompute_ms":..., "iteration_ms":...}
// (medians over the runs; implementations interleaved run by run), and the
// same-run ratios on stderr. Rows: eigen-ldlt, anisoform-arap,
// anisoform-anarap, anisoform-andefgrad, anisoform-preview (-shear,
// -rotate), anisoform-first-preview, anisoform-commit (CGAL has no WASM
// build). The module's code is shared by the rows' sessions: a row's first
// run can meet code V8 has not optimised yet, its later runs do not.
//
// Timings are taken in JS around the JS-layer calls, so they include what a
// browser caller pays: the layer's argument checks, the copy of the result
// into the float32 positions the views show, the result object.
//   eigen-ldlt           precompute: cotangent Laplacian, free block without
//                        the fixed vertices, Eigen SimplicialLDLT; iteration:
//                        one solve of 3 columns (median of 5)
//   anisoform-*          precompute: a fresh Deformer (setPositions of the
//                        exact rest positions) + the first deform()'s
//                        precompute; iteration: a second, warm-started
//                        deform() divided by its iterations (AnDefGrad: one
//                        change of amount, su 1.6/1.5, median of 4)
//   anisoform-preview    a slider's live preview (document/live-preview.js):
//                        precompute: a fresh Deformer + the first preview
//                        (factorization, the scale steps); iteration: one
//                        preview of a new amount (one warm-started AnARAP
//                        iteration) with the copy into the float32 buffer the
//                        worker transfers to the page (median of 9)
//   anisoform-preview-shear, anisoform-preview-rotate  the same with a shear
//                        (0.3 + 0.01 k) and a rotation about the normal
//                        (20 + k degrees)
//   anisoform-first-preview  as after a load in the app: precompute: the
//                        background preparation (Session.prepareStep to the
//                        end); iteration: the first stretch preview after it
//   anisoform-commit     a commit as the app makes one (document/op-stack.js):
//                        precompute: the op's first live preview (as the drag
//                        or slider before the release: the factorization);
//                        iteration: the commit, Session.replay of the op as a
//                        one-op document (a cold AnARAP stretch of the top
//                        half, box region, to the default tolerance)
// Environment: ANISO_WASM_DIR (default web/src/wasm), as the tests.
import { readFileSync } from 'node:fs';
import path from 'node:path';

import { loadAnisoform } from '../wasm/node-support.mjs';

const USAGE = `usage: node bench/wasm-bench.mjs --mesh cyl1k|cyl10k|cyl50k|cyl200k|PATH [--runs N]
                                 [--iterations N] [--only IMPL[,IMPL...]] [--verbose]
  --runs N        runs per implementation (medians); default 5, 3 above 100k vertices
  --iterations N  ARAP/AnARAP iterations per timed call (default 10)
  --only LIST     eigen-ldlt, anisoform-arap, anisoform-anarap, anisoform-andefgrad,
                  anisoform-preview, anisoform-preview-shear, anisoform-preview-rotate,
                  anisoform-first-preview, anisoform-commit (default: all)
  --verbose       per-run details on stderr
`;
const IMPLS = ['eigen-ldlt', 'anisoform-arap', 'anisoform-anarap', 'anisoform-andefgrad', 'anisoform-preview',
  'anisoform-preview-shear', 'anisoform-preview-rotate', 'anisoform-first-preview', 'anisoform-commit'];
const CYLINDERS = { cyl1k: 1000, cyl10k: 10000, cyl50k: 50000, cyl200k: 200000 };
const LDLT_SOLVES = 5;
const ANDEFGRAD_CHANGES = 4;
const PREVIEW_VALUES = 9;

function usageError(message) {
  process.stderr.write(`wasm-bench: ${message}\n${USAGE}`);
  process.exit(2);
}

function parseArguments(argv) {
  const options = { mesh: null, runs: 0, iterations: 10, only: new Set(), verbose: false };
  const positive = (name, text) => {
    const value = Number(text);
    if (!Number.isInteger(value) || value < 1) usageError(`${name} needs a positive integer, got '${text}'`);
    return value;
  };
  for (let a = 0; a < argv.length; ++a) {
    const arg = argv[a];
    const value = () => (a + 1 < argv.length ? argv[++a] : usageError(`${arg} needs a value`));
    if (arg === '--mesh') options.mesh = value();
    else if (arg === '--runs') options.runs = positive(arg, value());
    else if (arg === '--iterations') options.iterations = positive(arg, value());
    else if (arg === '--only') value().split(',').forEach((name) => options.only.add(name));
    else if (arg === '--verbose') options.verbose = true;
    else if (arg === '--help' || arg === '-h') {
      process.stdout.write(USAGE);
      process.exit(0);
    } else usageError(`unknown argument '${arg}'`);
  }
  if (!options.mesh) usageError('--mesh is required');
  for (const name of options.only) if (!IMPLS.includes(name)) usageError(`unknown implementation '${name}' in --only`);
  return options;
}

function median(values) {
  const sorted = [...values].sort((a, b) => a - b);
  const m = Math.floor(sorted.length / 2);
  return sorted.length % 2 ? sorted[m] : 0.5 * (sorted[m - 1] + sorted[m]);
}

function timed(call) {
  const start = performance.now();
  const result = call();
  return [performance.now() - start, result];
}

// bench/problems.cpp order_along: lowest (or highest) first along `axis`,
// ties by distance from the long axis line, then by index.
function orderAlong(positions, axis, centre, highestFirst) {
  const n = positions.length / 3;
  const key = new Float64Array(n);
  const radial = new Float64Array(n);
  for (let i = 0; i < n; ++i) {
    const p = [0, 1, 2].map((k) => positions[3 * i + k] - centre[k]);
    key[i] = highestFirst ? -p[axis] : p[axis];
    p[axis] = 0;
    radial[i] = p[0] * p[0] + p[1] * p[1] + p[2] * p[2];
  }
  return [...Array(n).keys()].sort((a, b) => key[a] - key[b] || radial[a] - radial[b] || a - b);
}

// The standard problem of bench/problems.cpp, from exact (float64) positions.
function makeProblem(name, positions) {
  const n = positions.length / 3;
  const min = [Infinity, Infinity, Infinity];
  const max = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < n; ++i) {
    for (let k = 0; k < 3; ++k) {
      min[k] = Math.min(min[k], positions[3 * i + k]);
      max[k] = Math.max(max[k], positions[3 * i + k]);
    }
  }
  const extent = max.map((x, k) => x - min[k]);
  let axis = 0;
  for (let k = 1; k < 3; ++k) if (extent[k] > extent[axis]) axis = k;
  const moveAxis = axis === 0 ? 1 : 0;
  const offset = [0, 0, 0];
  offset[moveAxis] = 0.25 * extent[axis];
  const direction = [0, 0, 0];
  direction[axis] = 1;
  const centre = min.map((x, k) => 0.5 * (x + max[k]));
  const count = Math.max(1, Math.round(0.05 * n));
  const fixed = orderAlong(positions, axis, centre, false).slice(0, count).sort((a, b) => a - b);
  const moved = orderAlong(positions, axis, centre, true).slice(0, count).sort((a, b) => a - b);
  const topHalf = new Float32Array(n);
  for (let i = 0; i < n; ++i) if (positions[3 * i + axis] > centre[axis]) topHalf[i] = 1;
  // The same half as a document region (a box includes its boundary).
  const topBox = { min: min.map((x, k) => (k === axis ? centre[axis] : x)), max };
  return { name, positions, vertices: n, axis, moveAxis, height: extent[axis], offset, direction, fixed, moved, topHalf,
    topBox };
}

// The problem, and `load(session)`, which puts its mesh in a session.
function loadProblem(wasm, name) {
  const session = new wasm.Session();
  try {
    if (name in CYLINDERS) {
      const { positions, triangles } = wasm.cappedCylinder(CYLINDERS[name], 1, 4);
      return { ...makeProblem(name, positions), load: (target) => target.setMesh(positions, triangles) };
    }
    const bytes = readFileSync(name);
    const load = (target) => target.loadMesh(bytes, path.basename(name));
    load(session);
    // Mesh files: the session's float32 positions (the reader's doubles are not exposed).
    return { ...makeProblem(name, Float64Array.from(session.positions())), load };
  } finally {
    session.delete();
  }
}

function runEigenLdlt(wasm, session, problem) {
  const [precompute, floor] = timed(() => new wasm.LaplacianFloor(session, problem.fixed));
  try {
    const times = [];
    for (let s = 0; s < LDLT_SOLVES; ++s) times.push(timed(() => floor.solve())[0]);
    return { precompute, iteration: median(times), detail: `first solve ${times[0].toFixed(3)} ms` };
  } finally {
    floor.delete();
  }
}

// A fresh Deformer, a cold first deform, then the same request warm-started.
function runIterative(session, problem, op) {
  const [setup] = timed(() => session.setPositions(problem.positions));
  const first = session.deform(op);
  const [second, result] = timed(() => session.deform(op));
  if (result.factorizations !== first.factorizations) throw new Error('a second deform() refactored');
  return {
    precompute: setup + first.precomputeMs,
    iteration: second / result.iterations,
    detail: `setup ${setup.toFixed(3)} ms, first call ${(first.solveMs / Math.max(first.iterations, 1)).toFixed(3)} ms/it, ${result.iterations} it`,
  };
}

function stretchOp(problem, method) {
  return { method, direction: { type: 'global', vector: problem.direction }, transform: { scale: 1.5 } };
}

function runArap(session, problem, iterations) {
  return runIterative(session, problem, {
    method: 'arap', pins: problem.fixed, handles: problem.moved, move: problem.offset, maxIterations: iterations, tolerance: 0,
  });
}

function runAnarap(session, problem, iterations) {
  session.setSelection(problem.topHalf);
  return runIterative(session, problem, { ...stretchOp(problem, 'anarap'), maxIterations: iterations, tolerance: 0 });
}

function runAndefgrad(session, problem) {
  const [setup] = timed(() => session.setPositions(problem.positions));
  session.setSelection(problem.topHalf);
  const op = stretchOp(problem, 'andefgrad');
  const first = session.deform(op);
  const times = [];
  let result;
  for (let c = 0; c < ANDEFGRAD_CHANGES; ++c) {
    const change = { ...op, transform: { scale: c % 2 === 0 ? 1.6 : 1.5 } };
    let time;
    [time, result] = timed(() => session.deform(change));
    times.push(time);
  }
  if (result.factorizations !== first.factorizations) throw new Error('a change of amount refactored');
  return { precompute: setup + first.precomputeMs, iteration: median(times), detail: `setup ${setup.toFixed(3)} ms` };
}

// The transforms of the preview rows, by the amount k (0, 1, ...).
const PREVIEW_TRANSFORMS = {
  'anisoform-preview': (k) => ({ scale: 1.5 + 0.01 * k }),
  'anisoform-preview-shear': (k) => ({ shear: 0.3 + 0.01 * k }),
  'anisoform-preview-rotate': (k) => ({ rotate: { axis: 'n', degrees: 20 + k } }),
};

function previewOf(session, problem, transform) {
  session.deform({ ...stretchOp(problem, 'anarap'), transform, warmStart: true, maxIterations: 1, preview: true });
  return session.positions().slice();
}

function runPreview(session, problem, transformAt) {
  const [setup] = timed(() => session.setPositions(problem.positions));
  session.setSelection(problem.topHalf);
  const [first] = timed(() => previewOf(session, problem, transformAt(0)));
  const times = [];
  for (let k = 1; k <= PREVIEW_VALUES; ++k) times.push(timed(() => previewOf(session, problem, transformAt(k)))[0]);
  return { precompute: setup + first, iteration: median(times), detail: `first preview ${first.toFixed(3)} ms` };
}

// As the app after a load: the background preparation (Session.prepareStep
// to the end), then a drag's first value.
function runFirstPreview(session, problem) {
  const [preparation, parts] = timed(() => {
    let count = 1;
    while (session.prepareStep() < 1) count++;
    return count;
  });
  session.setSelection(problem.topHalf);
  const [first] = timed(() => previewOf(session, problem, { scale: 1.5 }));
  return { precompute: preparation, iteration: first, detail: `${parts} parts` };
}

// The session holds the mesh as loaded (a fresh one): the replay starts there.
function runCommit(session, problem) {
  const region = { name: 'top', steps: [{ region: { box: problem.topBox } }] };
  session.setSelection(new Float32Array(problem.vertices));
  for (const step of region.steps) session.select(step.region);
  const op = session.resolveOp(stretchOp(problem, 'anarap'));
  const [preview] = timed(() => session.deform({ ...op, preview: true, maxIterations: 1 }));
  const { vertices, triangles } = session.info();
  const document = {
    format: 'anisoform-document',
    version: 1,
    mesh: { name: problem.name, vertices, triangles, hash: session.meshHash() },
    regions: [region],
    ops: [{ id: 'stretch', label: 'stretch', enabled: true, region: 'top', op }],
  };
  const factorizations = session.factorizations();
  const [commit, summary] = timed(() => session.replay(document));
  return { precompute: preview, iteration: commit,
    detail: `${summary.last.iterations} iterations, ${session.factorizations() - factorizations} new factorizations` };
}

async function main() {
  const options = parseArguments(process.argv.slice(2));
  const { wasm } = await loadAnisoform({ bench: true });
  const problem = loadProblem(wasm, options.mesh);
  // Every sample in a session of its own: a session keeps its previous rest
  // pose's Deformer (undo), so setPositions of positions it had before would
  // reuse that factorization and time no precompute.
  const inFreshSession = (run) => {
    const session = new wasm.Session();
    try {
      problem.load(session);
      return run(session);
    } finally {
      session.delete();
    }
  };
  const runs = options.runs || (problem.vertices > 100000 ? 3 : 5);
  const impls = {
    'eigen-ldlt': () => inFreshSession((session) => runEigenLdlt(wasm, session, problem)),
    'anisoform-arap': () => inFreshSession((session) => runArap(session, problem, options.iterations)),
    'anisoform-anarap': () => inFreshSession((session) => runAnarap(session, problem, options.iterations)),
    'anisoform-andefgrad': () => inFreshSession((session) => runAndefgrad(session, problem)),
    ...Object.fromEntries(Object.entries(PREVIEW_TRANSFORMS).map(([name, transformAt]) => [name,
      () => inFreshSession((session) => runPreview(session, problem, transformAt))])),
    'anisoform-first-preview': () => inFreshSession((session) => runFirstPreview(session, problem)),
    'anisoform-commit': () => inFreshSession((session) => runCommit(session, problem)),
  };
  const active = IMPLS.filter((name) => options.only.size === 0 || options.only.has(name));
  if (options.verbose) {
    process.stderr.write(`mesh ${problem.name}: ${problem.vertices} vertices; long axis ${'xyz'[problem.axis]} `
      + `(height ${problem.height}), move along ${'xyz'[problem.moveAxis]} by ${problem.offset[problem.moveAxis]}; `
      + `${problem.fixed.length} fixed, ${problem.moved.length} moved; ${runs} runs, ${options.iterations} iterations per call\n`);
  }
  // Interleaved, as the native bench: a slow phase of the machine hits every row alike.
  const samples = Object.fromEntries(active.map((name) => [name, []]));
  for (let r = 0; r < runs; ++r) {
    for (const name of active) {
      const sample = impls[name]();
      samples[name].push(sample);
      if (options.verbose) {
        process.stderr.write(`  run ${r} ${name.padEnd(20)} precompute ${sample.precompute.toFixed(3).padStart(9)} ms  `
          + `iteration ${sample.iteration.toFixed(3).padStart(8)} ms  (${sample.detail})\n`);
      }
    }
  }
  for (const name of active) {
    const row = {
      mesh: problem.name,
      vertices: problem.vertices,
      impl: name,
      precompute_ms: Number(median(samples[name].map((s) => s.precompute)).toFixed(3)),
      iteration_ms: Number(median(samples[name].map((s) => s.iteration)).toFixed(3)),
    };
    process.stdout.write(`${JSON.stringify(row)}\n`);
  }
  const ratio = (a, b, field) => {
    if (!samples[a] || !samples[b]) return 'n/a';
    return median(samples[a].map((s, k) => s[field] / samples[b][k][field])).toFixed(2);
  };
  process.stderr.write(`summary ${problem.name} WASM (${problem.vertices} vertices, ${runs} runs, same-run ratios, median): `
    + `arap/ldlt ${ratio('anisoform-arap', 'eigen-ldlt', 'iteration')} (goal <= 2.5), `
    + `anarap/ldlt ${ratio('anisoform-anarap', 'eigen-ldlt', 'iteration')} (goal <= 2.5), `
    + `andefgrad/ldlt ${ratio('anisoform-andefgrad', 'eigen-ldlt', 'iteration')} (goal <= 1.3), `
    + `precompute arap/ldlt ${ratio('anisoform-arap', 'eigen-ldlt', 'precompute')} (goal <= 1.5), `
    + `anarap/ldlt ${ratio('anisoform-anarap', 'eigen-ldlt', 'precompute')}, `
    + `andefgrad/ldlt ${ratio('anisoform-andefgrad', 'eigen-ldlt', 'precompute')}\n`);
  for (const [name, what] of [['anisoform-preview', 'stretch'], ['anisoform-preview-shear', 'shear'],
    ['anisoform-preview-rotate', 'rotation']]) {
    if (!samples[name]) continue;
    const ms = median(samples[name].map((s) => s.iteration));
    process.stderr.write(`preview ${problem.name} (${what}): ${ms.toFixed(1)} ms per slider value = `
      + `${(1000 / ms).toFixed(1)} updates/s (issue 11 goal 3: >= 30 at 50k vertices)\n`);
  }
  if (samples['anisoform-first-preview']) {
    const ms = median(samples['anisoform-first-preview'].map((s) => s.iteration));
    process.stderr.write(`first preview ${problem.name}: ${ms.toFixed(0)} ms after the background preparation\n`);
  }
  if (samples['anisoform-commit']) {
    const ms = median(samples['anisoform-commit'].map((s) => s.iteration));
    process.stderr.write(`commit ${problem.name}: ${ms.toFixed(0)} ms after a preview (issue 11 goal 4: <= 3000 at 200k vertices)\n`);
  }
}

main().catch((error) => {
  process.stderr.write(`wasm-bench: ${error.code ? `${error.code}: ` : ''}${error.message}\n`);
  process.exit(error.code === 'bad-parameter' ? 2 : 3);
});
