// Compressed and quantized versions of a GLB, made in Node with the tools
// product models are prepared with (glTF-Transform, Google's Draco encoder,
// meshoptimizer): the end-to-end tests open them in the app and compare the
// shape with the uncompressed file's.
import { NodeIO } from '../web/node_modules/@gltf-transform/core/dist/index.js';
import {
  EXTMeshGPUInstancing, EXTMeshoptCompression, KHRDracoMeshCompression, KHRMeshQuantization, KHRONOS_EXTENSIONS,
} from '../web/node_modules/@gltf-transform/extensions/dist/index.js';
import draco3d from '../web/node_modules/draco3dgltf/draco3dgltf.js';
import { MeshoptDecoder, MeshoptEncoder } from '../web/node_modules/meshoptimizer/index.js';

// One reader/writer for every file made (the Draco modules are compiled once).
let made = null;
function io() {
  made ??= makeIo();
  return made;
}

async function makeIo() {
  await Promise.all([MeshoptEncoder.ready, MeshoptDecoder.ready]);
  return new NodeIO()
    .registerExtensions([...KHRONOS_EXTENSIONS, EXTMeshoptCompression, EXTMeshGPUInstancing])
    .registerDependencies({
      'draco3d.encoder': await draco3d.createEncoderModule(),
      'draco3d.decoder': await draco3d.createDecoderModule(),
      'meshopt.encoder': MeshoptEncoder,
      'meshopt.decoder': MeshoptDecoder,
    });
}

/** `glb` with its geometry Draco-compressed (KHR_draco_mesh_compression, required; 14-bit positions). */
export async function dracoGlb(glb) {
  const files = await io();
  const document = await files.readBinary(new Uint8Array(glb));
  document.createExtension(KHRDracoMeshCompression).setRequired(true)
    .setEncoderOptions({ method: KHRDracoMeshCompression.EncoderMethod.EDGEBREAKER, quantizePosition: 14 });
  return Buffer.from(await files.writeBinary(document));
}

/**
 * `glb` with its positions quantized to 16-bit normalized integers
 * (KHR_mesh_quantization, required): each mesh's positions in its own box,
 * mapped to [-1, 1] and back by the node's scale and translation, as
 * gltfpack and glTF-Transform's quantize() write them.
 */
export async function quantizedGlb(glb) {
  const files = await io();
  const document = await files.readBinary(new Uint8Array(glb));
  document.createExtension(KHRMeshQuantization).setRequired(true);
  const quantized = new Set();
  for (const node of document.getRoot().listNodes()) {
    const mesh = node.getMesh();
    if (!mesh) continue;
    if (node.listChildren().length > 0) throw new Error('quantizedGlb: a mesh node with children');
    // Its dequantization goes into this node: another node could not share it.
    if (quantized.has(mesh)) throw new Error('quantizedGlb: a mesh used by two nodes');
    quantized.add(mesh);
    const positions = mesh.listPrimitives().map((primitive) => primitive.getAttribute('POSITION'));
    const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    for (const accessor of positions) {
      const min = accessor.getMin([]), max = accessor.getMax([]);
      for (let c = 0; c < 3; c++) {
        lo[c] = Math.min(lo[c], min[c]);
        hi[c] = Math.max(hi[c], max[c]);
      }
    }
    const center = lo.map((value, c) => (value + hi[c]) / 2);
    const half = Math.max(...lo.map((value, c) => (hi[c] - value) / 2));
    for (const accessor of new Set(positions)) {
      const source = accessor.getArray();
      const values = new Int16Array(source.length);
      for (let i = 0; i < source.length; i++) values[i] = Math.round(((source[i] - center[i % 3]) / half) * 32767);
      accessor.setArray(values).setNormalized(true);
    }
    // node = T R S; the dequantization (scale by half, then move by the
    // centre) goes under the node's own scale.
    const [sx, sy, sz] = node.getScale();
    if (node.getRotation().some((value, c) => value !== [0, 0, 0, 1][c])) {
      throw new Error('quantizedGlb: a rotated mesh node');
    }
    const [tx, ty, tz] = node.getTranslation();
    node.setScale([sx * half, sy * half, sz * half])
      .setTranslation([tx + sx * center[0], ty + sy * center[1], tz + sz * center[2]]);
  }
  return Buffer.from(await files.writeBinary(document));
}

/** `glb` with its buffers meshopt-compressed (EXT_meshopt_compression, required). */
export async function meshoptGlb(glb) {
  const files = await io();
  const document = await files.readBinary(new Uint8Array(glb));
  document.createExtension(EXTMeshoptCompression).setRequired(true)
    .setEncoderOptions({ method: EXTMeshoptCompression.EncoderMethod.QUANTIZE });
  return Buffer.from(await files.writeBinary(document));
}

/**
 * `glb` with its first mesh node drawn at `offsets` instead (each an [x, y, z]
 * translation; EXT_mesh_gpu_instancing, required), as scattered parts of a
 * product are shipped.
 */
export async function instancedGlb(glb, offsets) {
  const files = await io();
  const document = await files.readBinary(new Uint8Array(glb));
  const node = document.getRoot().listNodes().find((candidate) => candidate.getMesh());
  const translation = document.createAccessor().setType('VEC3').setArray(new Float32Array(offsets.flat()))
    .setBuffer(document.getRoot().listBuffers()[0]);
  const batch = document.createExtension(EXTMeshGPUInstancing).setRequired(true).createInstancedMesh()
    .setAttribute('TRANSLATION', translation);
  node.setExtension('EXT_mesh_gpu_instancing', batch);
  return Buffer.from(await files.writeBinary(document));
}

/**
 * `glb` with its first mesh rigged as a character is (a skin of two joints
 * under a root, every vertex bound half to each, in its rest pose):
 * JOINTS_0, WEIGHTS_0 and inverse bind matrices as exporters write them.
 */
export async function skinnedGlb(glb) {
  const files = await io();
  const document = await files.readBinary(new Uint8Array(glb));
  const root = document.getRoot();
  const buffer = root.listBuffers()[0];
  const node = root.listNodes().find((candidate) => candidate.getMesh());
  const hips = document.createNode('hips').setTranslation([0, 0.2, 0]);
  const spine = document.createNode('spine').setTranslation([0, 0.3, 0]);
  hips.addChild(spine);
  root.listScenes()[0].addChild(hips);
  // Each joint's inverse bind matrix: the inverse of its world matrix at rest (translations).
  const inverseBind = new Float32Array([
    1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -0.2, 0, 1,
    1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -0.5, 0, 1,
  ]);
  const skin = document.createSkin('rig').setSkeleton(hips).addJoint(hips).addJoint(spine)
    .setInverseBindMatrices(document.createAccessor().setType('MAT4').setArray(inverseBind).setBuffer(buffer));
  node.setSkin(skin);
  for (const primitive of node.getMesh().listPrimitives()) {
    const count = primitive.getAttribute('POSITION').getCount();
    const joints = new Uint16Array(4 * count);
    const weights = new Float32Array(4 * count);
    for (let i = 0; i < count; i++) {
      joints.set([0, 1, 0, 0], 4 * i);
      weights.set([0.5, 0.5, 0, 0], 4 * i);
    }
    primitive.setAttribute('JOINTS_0', document.createAccessor().setType('VEC4').setArray(joints).setBuffer(buffer));
    primitive.setAttribute('WEIGHTS_0', document.createAccessor().setType('VEC4').setArray(weights).setBuffer(buffer));
  }
  return Buffer.from(await files.writeBinary(document));
}
