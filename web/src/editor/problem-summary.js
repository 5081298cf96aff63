// Turns the mesh check's report (MeshInfo.problems and .notes) into a short
// notice in plain words: what the reader repaired, and what was found but can
// be edited through. Problems that block editing never get here: the worker
// refuses such meshes with an error and the current mesh stays.
// Keys are core/mesh_check's problem_kind_name spellings.
const KIND_WORDS = {
  'zero-area-triangle': ['zero-area triangle', 'zero-area triangles'],
  'repeated-corner': ['triangle using a vertex twice', 'triangles using a vertex twice'],
  'duplicate-face': ['duplicate triangle', 'duplicate triangles'],
  'non-manifold-edge': ['non-manifold edge', 'non-manifold edges'],
  'non-manifold-vertex': ['non-manifold vertex', 'non-manifold vertices'],
  'inconsistent-orientation': ['flipped triangle', 'flipped triangles'],
  'unreferenced-vertex': ['unused vertex', 'unused vertices'],
};

export function describeProblems(info) {
  const lines = [...(info.notes ?? [])];
  const byKind = new Map();
  for (const problem of info.problems ?? []) {
    const kind = problem.kind;
    if (!byKind.has(kind)) byKind.set(kind, []);
    byKind.get(kind).push(problem);
  }
  for (const [kind, problems] of byKind) {
    const [one, many] = KIND_WORDS[kind] ?? [kind, kind];
    const first = problems[0].message ? ` (first: ${problems[0].message})` : '';
    lines.push(`${problems.length} ${problems.length === 1 ? one : many}${first}.`);
  }
  if (info.components > 1) lines.push(`${info.components} separate parts: each keeps its own place.`);
  if (info.boundaryLoops > 0) {
    lines.push(`Open surface: ${info.boundaryLoops} boundary loop${info.boundaryLoops === 1 ? '' : 's'}.`);
  }
  return lines.join(' ');
}
