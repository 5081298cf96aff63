// glTF files for the export tests, made and read in Node with the page's own
// three.js: a product-like scene built from Spot's real UVs (OBJ from the
// shared meshes), as a modelling tool exports one: vertices split at the UV
// seams, normals, a named material, nodes with transforms, one geometry used
// by two nodes.
import { readFileSync } from 'node:fs';

import {
  BoxGeometry, BufferAttribute, Group, Mesh, MeshStandardMaterial, Vector3,
} from '../web/node_modules/three/build/three.module.js';
import { GLTFExporter } from '../web/node_modules/three/examples/jsm/exporters/GLTFExporter.js';
import { GLTFLoader } from '../web/node_modules/three/examples/jsm/loaders/GLTFLoader.js';
import { OBJLoader } from '../web/node_modules/three/examples/jsm/loaders/OBJLoader.js';
import { mergeVertices } from '../web/node_modules/three/examples/jsm/utils/BufferGeometryUtils.js';

// GLTFExporter's binary output goes through FileReader, which Node lacks.
class BlobReader {
  readAsArrayBuffer(blob) {
    blob.arrayBuffer().then((buffer) => {
      this.result = buffer;
      this.onloadend?.();
    });
  }
}

/**
 * Spot (OBJ with UVs) as an indexed geometry split at its UV seams, with
 * smooth normals: the copies of a seam vertex share the normal of the surface.
 */
function spotGeometry(objPath) {
  const group = new OBJLoader().parse(readFileSync(objPath, 'utf8'));
  const geometry = group.children[0].geometry;
  geometry.deleteAttribute('normal');
  const split = mergeVertices(geometry);
  const surface = geometry.clone();
  surface.deleteAttribute('uv');
  const welded = mergeVertices(surface);
  welded.computeVertexNormals();
  const key = (attribute, i) => `${attribute.getX(i)},${attribute.getY(i)},${attribute.getZ(i)}`;
  const normalAt = new Map();
  const weldedPosition = welded.getAttribute('position');
  const weldedNormal = welded.getAttribute('normal');
  for (let i = 0; i < weldedPosition.count; i++) normalAt.set(key(weldedPosition, i), i);
  const position = split.getAttribute('position');
  const normals = new Float32Array(position.count * 3);
  for (let i = 0; i < position.count; i++) {
    const j = normalAt.get(key(position, i));
    normals.set([weldedNormal.getX(j), weldedNormal.getY(j), weldedNormal.getZ(j)], 3 * i);
  }
  split.setAttribute('normal', new BufferAttribute(normals, 3));
  return split;
}

/**
 * The scene: 'product' (rotated, scaled, moved) holding 'body' and 'copy'
 * (both Spot's one geometry, 'copy' 3 units along x), material 'Hide', and
 * 'crate', a box with hard edges (each face its own normals) 3 units the
 * other way.
 * @returns {Promise<Buffer>} GLB bytes
 */
export async function spotSceneGlb(objPath) {
  const geometry = spotGeometry(objPath);
  const material = new MeshStandardMaterial({ name: 'Hide', color: 0xcc8844, roughness: 0.6 });
  const body = Object.assign(new Mesh(geometry, material), { name: 'body' });
  const copy = Object.assign(new Mesh(geometry, material), { name: 'copy' });
  copy.position.set(3, 0, 0);
  const crate = Object.assign(new Mesh(new BoxGeometry(0.5, 0.5, 0.5), material), { name: 'crate' });
  crate.position.set(-3, 0, 0);
  const product = Object.assign(new Group(), { name: 'product' });
  product.add(body, copy, crate);
  product.rotation.set(0.3, -0.5, 0.2);
  product.scale.setScalar(2);
  product.position.set(0.5, -1, 2);
  const hadReader = 'FileReader' in globalThis;
  if (!hadReader) globalThis.FileReader = BlobReader;
  try {
    return Buffer.from(await new GLTFExporter().parseAsync(product, { binary: true }));
  } finally {
    if (!hadReader) delete globalThis.FileReader;
  }
}

/** A GLB's scene, world matrices up to date (textures left out: Node has no image decoder). */
export async function parseGlb(bytes) {
  const buffer = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
  const withoutTextures = () => ({ name: 'no_textures_in_node', loadTexture: () => Promise.resolve(null) });
  const gltf = await new GLTFLoader().register(withoutTextures).parseAsync(buffer, '');
  gltf.scene.updateMatrixWorld(true);
  return gltf.scene;
}

/** The meshes of a scene by name: {geometry, matrixWorld, material, parentName}. */
export function meshesByName(scene) {
  const meshes = {};
  scene.traverse((object) => {
    if (object.isMesh) meshes[object.name] = object;
  });
  return meshes;
}

/** A mesh's vertex positions in world coordinates, xyz per vertex. */
export function worldPositions(mesh) {
  const position = mesh.geometry.getAttribute('position');
  const out = new Float64Array(position.count * 3);
  const point = new Vector3();
  for (let i = 0; i < position.count; i++) {
    point.fromBufferAttribute(position, i).applyMatrix4(mesh.matrixWorld);
    out.set([point.x, point.y, point.z], 3 * i);
  }
  return out;
}

/** A GLB's JSON chunk and binary chunk. */
export function glbChunks(glb) {
  const jsonLength = glb.readUInt32LE(12);
  const json = JSON.parse(glb.subarray(20, 20 + jsonLength).toString('utf8'));
  const binLength = glb.readUInt32LE(20 + jsonLength);
  return { json, bin: glb.subarray(28 + jsonLength, 28 + jsonLength + binLength) };
}

const padded = (bytes, fill) => Buffer.concat([bytes, Buffer.alloc((4 - (bytes.length % 4)) % 4, fill)]);

/** The GLB with `png` embedded as the base colour texture of its every material. */
export function withBaseColorTexture(glb, png) {
  const { json, bin } = glbChunks(glb);
  const binary = padded(Buffer.concat([padded(bin, 0), png]), 0);
  json.buffers[0].byteLength = binary.length;
  json.bufferViews.push({ buffer: 0, byteOffset: padded(bin, 0).length, byteLength: png.length });
  json.images = [{ bufferView: json.bufferViews.length - 1, mimeType: 'image/png' }];
  json.samplers = [{}];
  json.textures = [{ source: 0, sampler: 0 }];
  for (const material of json.materials) {
    material.pbrMetallicRoughness = { ...material.pbrMetallicRoughness, baseColorTexture: { index: 0 } };
  }
  return assembledGlb(json, binary);
}

/** The GLB of this JSON and binary chunk. */
export function assembledGlb(json, binary) {
  const text = padded(Buffer.from(JSON.stringify(json)), 0x20);
  const bin = padded(binary, 0);
  const header = Buffer.alloc(20);
  header.write('glTF', 0);
  header.writeUInt32LE(2, 4);
  header.writeUInt32LE(12 + 8 + text.length + 8 + bin.length, 8);
  header.writeUInt32LE(text.length, 12);
  header.writeUInt32LE(0x4e4f534a, 16); // 'JSON'
  const binHeader = Buffer.alloc(8);
  binHeader.writeUInt32LE(bin.length, 0);
  binHeader.writeUInt32LE(0x004e4942, 4); // 'BIN\0'
  return Buffer.concat([header, text, binHeader, bin]);
}

/** The GLB with its JSON changed by edit(json). */
export function glbWithJson(glb, edit) {
  const { json, bin } = glbChunks(glb);
  edit(json);
  return assembledGlb(json, bin);
}
