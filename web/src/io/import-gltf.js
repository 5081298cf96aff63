// GLB / glTF import with three.js's GLTFLoader: every triangle primitive of
// the scene, in world coordinates, merged into one indexed triangle list.
// Points and lines are skipped (and counted), as the core's OBJ reader does;
// skinned meshes are taken in their rest pose, instances as meshes of their
// own, and compressed geometry is decoded (gltf-decoders.js). The scene
// itself is kept (GltfSource), for a GLB export with its materials, UVs and
// nodes.
import { Group, Matrix4, Mesh, Scene, TextureLoader, Vector3 } from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';

import { prepareDecoders } from './gltf-decoders.js';
import { embeddedBuffersAsGlb } from './gltf-embedded.js';
import { GltfImportError } from './gltf-import-error.js';
import { GltfSource } from './gltf-source.js';

/** @returns {Promise<{positions: Float32Array, triangles: Uint32Array, notes: string[], source: GltfSource}>} */
export async function importGltf(bytes, name) {
  const json = gltfJson(bytes);
  // Geometry in other files cannot be read from a file opened in the page:
  // said as such, before GLTFLoader asks the page's server for them.
  const external = externalBufferUris(json);
  if (external.length > 0) {
    throw new GltfImportError(
      `${name} keeps its geometry in other files (${external.join(', ')}), which the page cannot read: ` +
        'open a .glb, or a .gltf with its buffers embedded (data: URIs).',
    );
  }
  const loader = new GLTFLoader().register(texturesAsImages);
  let gltf;
  let decoders = null;
  try {
    decoders = await prepareDecoders(loader, json);
    gltf = await loader.parseAsync(embeddedBuffersAsGlb(json, name) ?? bytes, '');
  } catch (error) {
    // DRACOLoader's workers reject with their message ({type: 'error', error}), not an Error.
    const reason = error?.message ?? (typeof error?.error === 'string' ? `Draco geometry: ${error.error}` : String(error));
    throw new GltfImportError(`${name}: not a readable glTF file: ${reason}`);
  } finally {
    decoders?.dispose();
  }
  // A file may list no scene (GLTFLoader then gives none): nothing is placed to show.
  if (!gltf.scene) throw new GltfImportError(`${name}: the glTF file has no scene (its "scenes" list is empty or missing), so no mesh is placed to show.`);
  // GLTFLoader's scene is a Group, which GLTFExporter would write as a node
  // of a new scene: one more wrapper node at every round trip.
  const scene = Object.assign(new Scene(), { name: gltf.scene.name });
  scene.add(...gltf.scene.children);
  const instances = separateInstances(scene);
  scene.updateMatrixWorld(true);

  const parts = [];
  let skipped = 0;
  let skinned = 0;
  scene.traverse((object) => {
    // A skinned (rigged) mesh is edited in its rest pose, as the file
    // stores it: its skin (joints, weights, bind matrices) is kept, so the
    // edited shape follows the rig as the old one did. Points and lines
    // have no surface.
    if (object.isMesh && object.geometry.getAttribute('position')) {
      parts.push(object);
      if (object.isSkinnedMesh) skinned++;
    } else if (object.isLine || object.isPoints) {
      skipped++;
    }
  });
  if (parts.length === 0) throw new GltfImportError(`${name}: the glTF scene contains no triangle mesh.`);

  let vertexTotal = 0;
  let indexTotal = 0;
  for (const mesh of parts) {
    const geometry = mesh.geometry;
    vertexTotal += geometry.getAttribute('position').count;
    indexTotal += geometry.index ? geometry.index.count : geometry.getAttribute('position').count;
  }
  const positions = new Float32Array(vertexTotal * 3);
  const triangles = new Uint32Array(indexTotal);
  const point = new Vector3();
  const toWorld = new Matrix4();
  let vertexOffset = 0;
  let indexOffset = 0;
  const sourceParts = [];
  const geometries = new Set();
  for (const mesh of parts) {
    // A geometry two nodes share is edited apart in each: each its own copy.
    if (geometries.has(mesh.geometry)) mesh.geometry = mesh.geometry.clone();
    geometries.add(mesh.geometry);
    sourceParts.push({ mesh, offset: vertexOffset });
    const geometry = mesh.geometry;
    const position = geometry.getAttribute('position');
    toWorld.copy(mesh.matrixWorld);
    for (let i = 0; i < position.count; i++) {
      point.fromBufferAttribute(position, i);
      // A malformed accessor or bufferView (a byteStride of 0.5) reads as NaN:
      // said of the mesh and its POSITION, not of a merged vertex number.
      if (!Number.isFinite(point.x + point.y + point.z)) {
        throw new GltfImportError(`${name}: mesh '${mesh.name || mesh.uuid.slice(0, 8)}' has a non-finite position at its vertex ${i} ` +
          '(its POSITION accessor or bufferView is malformed).');
      }
      point.applyMatrix4(toWorld);
      const at = (vertexOffset + i) * 3;
      positions[at] = point.x;
      positions[at + 1] = point.y;
      positions[at + 2] = point.z;
    }
    if (geometry.index) {
      const index = geometry.index;
      for (let k = 0; k < index.count; k++) triangles[indexOffset + k] = vertexOffset + index.getX(k);
      indexOffset += index.count;
    } else {
      for (let k = 0; k < position.count; k++) triangles[indexOffset + k] = vertexOffset + k;
      indexOffset += position.count;
    }
    vertexOffset += position.count;
  }
  if (indexOffset % 3 !== 0) {
    throw new GltfImportError(`${name}: a triangle list has ${indexOffset} indices, not a multiple of 3.`);
  }

  const notes = [];
  if (parts.length > 1) notes.push(`${parts.length} meshes of the glTF scene were merged into one.`);
  if (skipped > 0) notes.push(`${skipped} point or line objects were skipped.`);
  if (skinned > 0) {
    notes.push(`${skinned} skinned (rigged) mesh${skinned === 1 ? ' is' : 'es are'} edited in the rest pose; the skin is kept.`);
  }
  if (instances > 0) {
    notes.push(`${instances} instances (EXT_mesh_gpu_instancing) became meshes of their own, and export as such.`);
  }
  if (decoders.compressed.length > 0) {
    notes.push(`The file's geometry is ${decoders.compressed.join(' and ')}-compressed: a GLB export writes it uncompressed.`);
  }
  if (decoders.unread.length > 0) {
    notes.push(
      `The file uses glTF extensions this app does not read (${decoders.unread.join(', ')}): ` +
        'what they add is not shown, and a GLB export leaves it out.',
    );
  }
  return { positions, triangles, notes, source: new GltfSource(scene, sourceParts) };
}

// Each instance of an instanced mesh (EXT_mesh_gpu_instancing) as a mesh of
// its own, at its place under the same parent: instances share one geometry
// placed many times, and an edit moves each where it lies. Returns how many.
function separateInstances(scene) {
  const instanced = [];
  scene.traverse((object) => {
    if (object.isInstancedMesh) instanced.push(object);
  });
  let count = 0;
  for (const object of instanced) {
    const group = new Group();
    group.name = object.name;
    group.matrix.copy(object.matrix);
    group.matrix.decompose(group.position, group.quaternion, group.scale);
    for (let i = 0; i < object.count; i++) {
      const mesh = new Mesh(object.geometry, object.material);
      mesh.name = `${object.name || 'instance'}.${i}`;
      object.getMatrixAt(i, mesh.matrix);
      mesh.matrix.decompose(mesh.position, mesh.quaternion, mesh.scale);
      group.add(mesh);
    }
    count += object.count;
    // In the instanced mesh's place among its parent's children (the export's node order).
    const parent = object.parent;
    parent.children[parent.children.indexOf(object)] = group;
    group.parent = parent;
    object.parent = null;
  }
  return count;
}

// Embedded textures decoded as <img> from their blob: URL (CSP img-src), not
// fetched (GLTFLoader's ImageBitmapLoader, where browsers have it), which the
// page's connect-src refuses: the textures were lost, with a CSP violation
// at every load of a textured GLB.
function texturesAsImages(parser) {
  parser.textureLoader = new TextureLoader(parser.options.manager);
  return { name: 'anisoform_textures_as_images' };
}

// The glTF JSON of a .gltf or of a .glb's JSON chunk; null for what does
// not parse (GLTFLoader says what is wrong with it).
function gltfJson(bytes) {
  const view = new Uint8Array(bytes.buffer ?? bytes, bytes.byteOffset ?? 0, bytes.byteLength);
  let text = null;
  const isGlb = view.length >= 20 && String.fromCharCode(...view.subarray(0, 4)) === 'glTF';
  if (isGlb) {
    const data = new DataView(view.buffer, view.byteOffset, view.byteLength);
    const length = data.getUint32(12, true);
    if (data.getUint32(16, true) === 0x4e4f534a && 20 + length <= view.length) { // 'JSON'
      text = new TextDecoder().decode(view.subarray(20, 20 + length));
    }
  } else {
    text = new TextDecoder().decode(view);
  }
  try {
    const json = JSON.parse(text);
    return json && typeof json === 'object' ? json : null;
  } catch {
    return null;
  }
}

// The buffer URIs of a glTF's JSON that name other files rather than data:
// URIs or the GLB's own binary chunk.
function externalBufferUris(json) {
  const buffers = json?.buffers;
  if (!Array.isArray(buffers)) return [];
  return buffers.map((buffer) => buffer?.uri).filter((uri) => typeof uri === 'string' && !uri.startsWith('data:'));
}
