// Turns the mesh check's report (MeshInfo.problems and .notes) into a short
// notice in plain words: what the reader repaired, and what was found but can
// be edited through, one sentence each, with a kind's count and first few
// elements instead of the full list; the full list goes into `details`
// (shown on demand). Problems that block editing never get here: the worker
// refuses such meshes with an error and the current mesh stays.
// Keys are core/mesh_check's problem_kind_name spellings; the element is the
// problem's face or vertex index (mesh_check's Problem::element).
const KIND_WORDS = {
  'zero-area-triangle': ['zero-area triangle', 'zero-area triangles', 'face'],
  'repeated-corner': ['triangle using a vertex twice', 'triangles using a vertex twice', 'face'],
  'duplicate-face': ['duplicate triangle', 'duplicate triangles', 'face'],
  // The element of an edge problem is one of the faces at that edge.
  'non-manifold-edge': ['non-manifold edge', 'non-manifold edges', 'at face'],
  'non-manifold-vertex': ['non-manifold vertex', 'non-manifold vertices', 'vertex'],
  'inconsistent-orientation': ['flipped triangle', 'flipped triangles', 'face'],
  'unreferenced-vertex': ['unused vertex', 'unused vertices', 'vertex'],
};
const PLURAL = { face: 'faces', 'at face': 'at faces', vertex: 'vertices' };
// Elements named in the summary sentence, and problem sentences in the details.
const FIRST_ELEMENTS = 3;
const MAX_DETAILS = 200;

/** {message, details} for a load's report, or null when there is nothing to say. */
export function describeProblems(info) {
  const lines = (info.notes ?? []).map(sentence);
  const byKind = new Map();
  for (const problem of info.problems ?? []) {
    if (!byKind.has(problem.kind)) byKind.set(problem.kind, []);
    byKind.get(problem.kind).push(problem);
  }
  for (const [kind, problems] of byKind) {
    const [one, many, noun] = KIND_WORDS[kind] ?? [kind, kind, 'element'];
    // The core lists the first 1000 of a kind and counts them all (problemCounts).
    const count = info.problemCounts?.[kind] ?? problems.length;
    lines.push(`${count} ${count === 1 ? one : many}${elementList(problems, noun, count)}.`);
  }
  if (info.components > 1) lines.push(`${info.components} separate parts: each keeps its own place.`);
  const far = farFromOrigin(info.bbox);
  if (far) lines.push(far);
  // Whether the surface is open is no problem and not news: the status bar
  // says it (openSurface). As a notice it covered the top of every open
  // mesh's view, a third of a phone's in Flatten mode, until dismissed.
  if (lines.length === 0) return null;
  return { message: lines.join(' '), details: problemDetails(info.problems ?? [], info.problemCounts) };
}

/** The status bar's word on the surface: {text: ' · open', title: 'Open surface: 5 boundary loops'}, or none when closed. */
export function openSurface(info) {
  const loops = info.boundaryLoops ?? 0;
  if (loops === 0) return { text: '', title: 'Closed surface' };
  return { text: ' · open', title: `Open surface: ${loops} boundary loop${loops === 1 ? '' : 's'}` };
}

// " (face 3)", " (faces 3, 17)", " (first: faces 3, 17, 40 …)", " (first at faces 3, 17, 40 …)".
function elementList(problems, noun, count = problems.length) {
  const elements = problems.map((problem) => problem.element).filter((element) => element >= 0);
  if (elements.length === 0) return '';
  const shown = elements.slice(0, FIRST_ELEMENTS).join(', ');
  const name = elements.length === 1 ? noun : (PLURAL[noun] ?? `${noun}s`);
  if (elements.length <= FIRST_ELEMENTS && count <= elements.length) return ` (${name} ${shown})`;
  return ` (first${name.startsWith('at ') ? ' ' : ': '}${name} ${shown} …)`;
}

function problemDetails(problems, counts) {
  const details = problems.slice(0, MAX_DETAILS).map((problem) => sentence(problem.message));
  const total = counts ? Object.values(counts).reduce((sum, count) => sum + count, 0) : problems.length;
  if (total > details.length) details.push(`… and ${total - details.length} more.`);
  return details;
}

// The core's notes and messages are lower-case clauses; a notice is sentences.
function sentence(text) {
  const trimmed = String(text).trim();
  return `${trimmed.charAt(0).toUpperCase()}${trimmed.slice(1)}`.replace(/\.?$/, '.');
}

// The view and the GLB / binary STL files hold positions as 32-bit floats,
// whose spacing grows with the distance from the origin: a mesh 1 unit
// across at 1e6 drew as a stepped, torn cow of 16 distinct x values. Said
// when that spacing is over a thousandth of the mesh's size (the core's
// solve and the OBJ, OFF and PLY files keep doubles).
const FLOAT32_STEP = 2 ** -23;
export function farFromOrigin(bbox) {
  if (!bbox) return null;
  const { min, max } = bbox;
  const farthest = Math.max(...min.map(Math.abs), ...max.map(Math.abs));
  const size = Math.hypot(max[0] - min[0], max[1] - min[1], max[2] - min[2]);
  if (!(size > 0) || farthest * FLOAT32_STEP <= 1e-3 * size) return null;
  return `The mesh lies far from the origin for its size (${farthest.toPrecision(3)} units away, ${size.toPrecision(3)} across): ` +
    'the view draws it in 32-bit floats, so it may look stepped or torn, and GLB and binary STL files hold 32-bit floats; ' +
    'the edits and OBJ, OFF and PLY exports keep its full precision. Moving it near the origin in the program it came from avoids this.';
}
