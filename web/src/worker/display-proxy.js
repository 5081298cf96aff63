// The simplified mesh the page draws while a big mesh moves on a CPU
// rasteriser (viewer/interaction-proxy.js), computed in the solver worker so
// that the page's main thread never pays for it (meshoptimizer's quadric
// simplifier: 207 ms for 52k triangles, 1 s for 400k). Its vertices are a
// subset of the mesh's own, so each frame only gathers their positions.
import { MeshoptSimplifier } from 'meshoptimizer/simplifier';

/**
 * About `targetTriangles` triangles of the mesh (positions: 3 per vertex,
 * triangles: 3 indices each): `vertices`, the mesh's index of each of its
 * vertices, and `triangles` over those.
 */
export async function simplifiedMesh(positions, triangles, targetTriangles) {
  await MeshoptSimplifier.ready;
  // The simplifier stops at the target, not at an error bound: its error is
  // relative to the mesh's extent, and 1 is the whole mesh.
  const [index] = MeshoptSimplifier.simplify(new Uint32Array(triangles), positions, 3, 3 * targetTriangles, 1);
  const proxyVertex = new Map();
  const compact = new Uint32Array(index.length);
  for (let i = 0; i < index.length; i++) {
    let p = proxyVertex.get(index[i]);
    if (p === undefined) {
      p = proxyVertex.size;
      proxyVertex.set(index[i], p);
    }
    compact[i] = p;
  }
  return { vertices: Uint32Array.from(proxyVertex.keys()), triangles: compact };
}
