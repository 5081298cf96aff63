// Export of the current mesh as GLB, with three.js's GLTFExporter, for a mesh
// not opened from a glTF file (that one goes back into its own scene,
// gltf-source.js); the core has no glTF writer (OBJ, PLY and STL are the
// core's, in the worker; see Editor.export). The mesh is rebuilt from the
// solver's positions and triangles and what its file carried that glTF has a
// place for (Session.surfaceAttributes): an OBJ's texture coordinates (a
// vertex split where its corners' coordinates differ: UV seams) and material
// names (one primitive each), an OBJ's or a PLY's vertex colours. Editor-only
// attributes (selection, heat map) never leak out.
import { BufferAttribute, BufferGeometry, Color, Mesh, MeshStandardMaterial, SRGBColorSpace } from 'three';
import { GLTFExporter } from 'three/addons/exporters/GLTFExporter.js';

import { weldedNormals } from './welded-normals.js';

/**
 * @param {Float32Array} positions  xyz per vertex
 * @param {Uint32Array} triangles
 * @param {string} name  the mesh's name in the file
 * @param {{cornerUv: Float32Array|null, colors: Float32Array|null, materials: {name: string, first: number}[]}|null} surface
 * @returns {Promise<ArrayBuffer>}
 */
export async function exportGlb(positions, triangles, name = 'anisoform', surface = null) {
  const geometry = surfaceGeometry(positions, triangles, surface);
  const materials = materialGroups(geometry, triangles.length / 3, surface?.materials ?? [], geometry.hasAttribute('color'));
  const mesh = new Mesh(geometry, materials.length === 1 ? materials[0] : materials);
  mesh.name = name;
  try {
    return await new GLTFExporter().parseAsync(mesh, { binary: true });
  } finally {
    geometry.dispose();
    for (const material of materials) material.dispose();
  }
}

// Positions, unit normals (one per solver vertex, so smooth across UV
// seams), the texture coordinates and colours given, and the index. With
// texture coordinates, a solver vertex becomes one file vertex per distinct
// (u, v) among its corners.
function surfaceGeometry(positions, triangles, surface) {
  const normals = weldedNormals(positions, triangles);
  for (let i = 0; i < normals.length; i += 3) {
    const length = Math.hypot(normals[i], normals[i + 1], normals[i + 2]) || 1;
    normals[i] /= length;
    normals[i + 1] /= length;
    normals[i + 2] /= length;
  }
  // (Sizes checked: attributes of another mesh than this one are left out.)
  const colors = surface?.colors?.length === positions.length ? linearColors(surface.colors) : null;
  const cornerUv = surface?.cornerUv?.length === 2 * triangles.length ? surface.cornerUv : null;
  // Which solver vertex each file vertex is, and its (u, v): file vertex i
  // is solver vertex i with its first corner's (u, v) (so the file keeps the
  // solver's vertex order, and reads back welded as it was), then one more
  // for each other (u, v) a vertex's corners have.
  let source = null;
  let uv = null;
  let index = triangles;
  if (cornerUv) {
    const n = positions.length / 3;
    source = Array.from({ length: n }, (_, i) => i);
    const uvs = Array(2 * n).fill(0);
    const assigned = new Uint8Array(n);
    const copies = new Map();
    index = new Uint32Array(triangles.length);
    for (let corner = 0; corner < triangles.length; corner++) {
      const v = triangles[corner];
      const u = cornerUv[2 * corner], w = cornerUv[2 * corner + 1];
      if (!assigned[v]) {
        assigned[v] = 1;
        uvs[2 * v] = u;
        uvs[2 * v + 1] = w;
      }
      if (uvs[2 * v] === u && uvs[2 * v + 1] === w) {
        index[corner] = v;
        continue;
      }
      const key = `${v} ${u} ${w}`;
      let at = copies.get(key);
      if (at === undefined) {
        at = source.length;
        copies.set(key, at);
        source.push(v);
        uvs.push(u, w);
      }
      index[corner] = at;
    }
    uv = new Float32Array(uvs);
  }
  const count = source ? source.length : positions.length / 3;
  const take = (values) => {
    if (!source) return new Float32Array(values);
    const out = new Float32Array(3 * count);
    for (let i = 0; i < count; i++) out.set(values.subarray(3 * source[i], 3 * source[i] + 3), 3 * i);
    return out;
  };
  const geometry = new BufferGeometry();
  geometry.setAttribute('position', new BufferAttribute(take(positions), 3));
  geometry.setAttribute('normal', new BufferAttribute(take(normals), 3));
  if (uv) geometry.setAttribute('uv', new BufferAttribute(uv, 2));
  if (colors) geometry.setAttribute('color', new BufferAttribute(take(colors), 3));
  geometry.setIndex(new BufferAttribute(new Uint32Array(index), 1));
  return geometry;
}

// glTF's COLOR_0 is linear (three.js's working space); OBJ and PLY colours
// are sRGB-encoded (as three.js's PLYLoader reads them).
function linearColors(colors) {
  const out = new Float32Array(colors.length);
  const color = new Color();
  for (let i = 0; i < colors.length; i += 3) {
    color.setRGB(colors[i], colors[i + 1], colors[i + 2], SRGBColorSpace).toArray(out, i);
  }
  return out;
}

// One material per OBJ material run (named as in the file; the .mtl's
// contents were not read), as geometry groups: one primitive each. Triangles
// before the first usemtl get an unnamed one.
function materialGroups(geometry, triangleCount, runs, vertexColors) {
  const material = (materialName) => {
    const made = new MeshStandardMaterial({ vertexColors });
    made.name = materialName;
    return made;
  };
  if (runs.length === 0) return [material('')];
  const starts = runs[0].first > 0 ? [{ name: '', first: 0 }, ...runs] : runs;
  const materials = [];
  for (const [k, run] of starts.entries()) {
    const end = k + 1 < starts.length ? starts[k + 1].first : triangleCount;
    if (end <= run.first) continue;
    geometry.addGroup(3 * run.first, 3 * (end - run.first), materials.length);
    materials.push(material(run.name));
  }
  return materials;
}
