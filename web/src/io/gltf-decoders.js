// Decoders for compressed glTF geometry, loaded the first time a file needs
// them: Draco (KHR_draco_mesh_compression) and meshopt
// (EXT_meshopt_compression), the two that product models are usually
// shipped with. KHR_mesh_quantization needs none (GLTFLoader reads it).

// What GLTFLoader reads (its EXTENSIONS, three 0.187): a file using anything
// else is told which of its extensions are left out (KHR_texture_basisu's
// textures, for one, are neither shown nor exported).
const READ_EXTENSIONS = new Set([
  'KHR_binary_glTF', 'KHR_draco_mesh_compression', 'KHR_lights_punctual', 'KHR_materials_clearcoat',
  'KHR_materials_diffuse_roughness', 'KHR_materials_dispersion', 'KHR_materials_ior', 'KHR_materials_sheen',
  'KHR_materials_specular', 'KHR_materials_transmission', 'KHR_materials_iridescence', 'KHR_materials_anisotropy',
  'KHR_materials_unlit', 'KHR_materials_volume', 'KHR_texture_transform', 'KHR_mesh_quantization',
  'KHR_materials_emissive_strength', 'EXT_materials_bump', 'EXT_texture_webp', 'EXT_texture_avif',
  'EXT_meshopt_compression', 'KHR_meshopt_compression', 'EXT_mesh_gpu_instancing',
]);
const MESHOPT = ['EXT_meshopt_compression', 'KHR_meshopt_compression'];

/**
 * Sets up `loader` (a GLTFLoader) for the extensions `json` (the file's glTF
 * JSON, or null) uses, and returns what to do when the parse is over
 * (`dispose`: the Draco decoder's workers end), the compressions it uses
 * (which a GLB export does not write again) and the extensions left out.
 * @returns {Promise<{dispose: () => void, compressed: string[], unread: string[]}>}
 */
export async function prepareDecoders(loader, json) {
  const used = Array.isArray(json?.extensionsUsed) ? json.extensionsUsed.filter((name) => typeof name === 'string') : [];
  const compressed = [];
  let draco = null;
  if (used.includes('KHR_draco_mesh_compression')) {
    // three.js's decoder files for glTF, found beside DRACOLoader.js (new
    // URL(..., import.meta.url)): the site's build emits them, an embedder's
    // bundler or server finds them with three.js.
    const { DRACOLoader, DRACO_GLTF_CONFIG } = await import('three/addons/loaders/DRACOLoader.js');
    draco = new DRACOLoader().setDecoderPath(DRACO_GLTF_CONFIG).setWorkerLimit(2);
    loader.setDRACOLoader(draco);
    compressed.push('Draco');
  }
  if (used.some((name) => MESHOPT.includes(name))) {
    const { MeshoptDecoder } = await import('meshoptimizer/decoder');
    await MeshoptDecoder.ready;
    loader.setMeshoptDecoder(MeshoptDecoder);
    compressed.push('meshopt');
  }
  return {
    dispose: () => draco?.dispose(),
    compressed,
    unread: used.filter((name) => !READ_EXTENSIONS.has(name)),
  };
}
