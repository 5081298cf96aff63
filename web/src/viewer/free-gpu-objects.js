// Frees the GL buffers, textures and programs three.js made for what an
// object holds (its subtree's geometries, materials and their textures). The
// objects stay usable: drawn again, they are uploaded again. Why: a WebGL
// context that outlives what it drew (a renderer handed to the next modeller:
// solver-pool.js) keeps those GL objects until they are disposed.
export function freeGpuObjects(root) {
  root.traverse((object) => {
    object.geometry?.dispose();
    for (const material of [object.material ?? []].flat()) {
      for (const value of Object.values(material)) if (value?.isTexture) value.dispose();
      material.dispose();
    }
  });
}
