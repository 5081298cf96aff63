// The file's own look: a mesh opened from glTF drawn as its scene, with its
// materials, textures and vertex colours, in the shape being edited (the
// committed one and every live preview frame), in place of the editing
// surface (which shows the selection and heat maps). The scene is the
// GltfSource's (io/gltf-source.js), the one a GLB export writes: drawn here
// it has the shape on screen, and an export writes the committed one again.
// The editing surface lights itself (its shader); the file's materials need
// lights: a sky/ground fill and a key light that turns with the camera.
import { DirectionalLight, HemisphereLight } from 'three';
import { freeGpuObjects } from './free-gpu-objects.js';

export class GltfDisplay {
  /** @type {import('../io/gltf-source.js').GltfSource | null} */
  #source = null;
  #wanted = false;
  #positions = null;
  #triangles = null;
  #written = null; // the positions the scene holds
  #live = false; // they are a live preview frame's: normals not recomputed

  constructor(viewer, meshView) {
    this.viewer = viewer;
    this.meshView = meshView;
    this.fill = new HemisphereLight(0xffffff, 0x40444c, 1.8);
    this.key = new DirectionalLight(0xffffff, 2.2);
    this.key.position.set(0.4, 0.8, 1); // above and to the right of the eye
    this.key.target.position.set(0, 0, -1);
    this.key.add(this.key.target);
    this.#sync();
  }

  /** The loaded mesh's glTF scene, or null (other formats). */
  setSource(source, positions, triangles) {
    if (this.#source && this.#source !== source) {
      this.viewer.scene.remove(this.#source.scene);
      // Its GL objects, drawn or not, go with it (the context may outlive this modeller).
      freeGpuObjects(this.#source.scene);
    }
    this.#source = source ?? null;
    this.#triangles = triangles;
    this.#positions = positions;
    this.#written = null;
    this.#sync();
  }

  /** At the modeller's dispose: frees the shown glTF scene's GL objects, in the scene or not. */
  dispose() {
    if (this.#source) freeGpuObjects(this.#source.scene);
  }

  /** Whether the file's look is wanted (the display setting). */
  setWanted(wanted) {
    this.#wanted = wanted;
    this.#sync();
  }

  /** {live: true}: a preview frame while something is dragged (normals wait for the commit). */
  showPositions(positions, { live = false } = {}) {
    this.#positions = positions;
    this.#live = live;
    if (this.active) this.#write();
  }

  /** The file's look is on screen. */
  get active() {
    return this.#wanted && this.#source !== null;
  }

  #write() {
    if (this.#written === this.#positions) return;
    this.#source.writeShape(this.#positions, this.#triangles, { normals: !this.#live });
    // A live frame's array is reused for the next one: written again each time.
    this.#written = this.#live ? null : this.#positions;
    this.viewer.requestRender();
  }

  #sync() {
    const active = this.active;
    const { scene, camera } = this.viewer;
    if (active) {
      this.#write();
      if (!this.#source.scene.parent) scene.add(this.#source.scene);
      // The key light rides on the camera, which then has to be in the scene.
      scene.add(this.fill, camera);
      camera.add(this.key);
    } else {
      if (this.#source?.scene.parent) scene.remove(this.#source.scene);
      scene.remove(this.fill, camera);
      camera.remove(this.key);
    }
    this.meshView.setSurfaceVisible(!active);
    // For tests and assistive tools: what the surface is drawn with.
    this.viewer.canvas.dataset.surface = active ? 'materials' : 'editing';
    this.viewer.requestRender();
  }
}
