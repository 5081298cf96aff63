// A big mesh's GPU buffers go up over a few frames before it is first drawn.
//
// Why: three uploads all the buffers of a geometry in the frame that first
// draws it. For an 800k-vertex scan that is 45 MB (positions, normals,
// selection weights, distortion values, the index) and one main-thread task
// of 300 ms under SwiftShader on 2 cores: the page froze right after the load.
// Each frame here draws, instead, a helper mesh holding the next buffers with
// nothing to draw (draw range 0): three uploads a buffer the first time a
// drawn geometry holds it and keeps it per attribute, so when the mesh itself
// is drawn, its buffers are on the GPU already. A mesh whose buffers fit in
// one step is drawn at once, as before.
import { BufferGeometry, Mesh, Sphere } from 'three';

/** Bytes uploaded in one frame at most (a larger buffer goes alone): about 90 ms under SwiftShader. */
export const STEP_BYTES = 16 * 2 ** 20;

/** The geometry's buffers, [name, attribute] ('index' for the index), grouped into steps of at most STEP_BYTES. */
export function uploadSteps(geometry) {
  const buffers = Object.entries(geometry.attributes);
  if (geometry.index) buffers.push(['index', geometry.index]);
  const steps = [];
  let bytes = Infinity;
  for (const buffer of buffers) {
    const size = buffer[1].array.byteLength;
    if (bytes + size > STEP_BYTES) {
      steps.push([]);
      bytes = 0;
    }
    steps[steps.length - 1].push(buffer);
    bytes += size;
  }
  return steps;
}

export class StagedUpload {
  #viewer;
  #material;
  #helper = null;
  #stopListening = null;

  /** material: the one the mesh is drawn with (its program is compiled by the first step, not by the first draw). */
  constructor(viewer, material) {
    this.#viewer = viewer;
    this.#material = material;
  }

  /**
   * Uploads the geometry's buffers a step per frame, then calls shown():
   * within this call when they fit in one step. An upload in progress is
   * abandoned (a newer mesh came).
   */
  upload(geometry, shown) {
    this.cancel();
    const steps = uploadSteps(geometry);
    if (steps.length <= 1) {
      shown();
      return;
    }
    const helper = new Mesh(new BufferGeometry(), this.#material);
    helper.geometry.setDrawRange(0, 0);
    // Never culled, and no bounding sphere to compute over its positions.
    helper.frustumCulled = false;
    helper.geometry.boundingSphere = new Sphere();
    this.#helper = helper;
    this.#viewer.scene.add(helper);
    let next = 0;
    const step = () => {
      if (next === steps.length) {
        this.cancel();
        shown();
        return;
      }
      for (const [name, attribute] of steps[next++]) {
        if (name === 'index') helper.geometry.setIndex(attribute);
        else helper.geometry.setAttribute(name, attribute);
      }
      this.#viewer.requestRender();
    };
    this.#stopListening = this.#viewer.on('frame', step);
    step();
  }

  /** Drops the helper; the buffers it uploaded stay with their attributes (the mesh's). */
  cancel() {
    this.#stopListening?.();
    this.#stopListening = null;
    const helper = this.#helper;
    if (!helper) return;
    this.#helper = null;
    this.#viewer.scene.remove(helper);
    // Emptied first: disposing a geometry deletes the GPU buffers of what it holds.
    for (const name of Object.keys(helper.geometry.attributes)) helper.geometry.deleteAttribute(name);
    helper.geometry.setIndex(null);
    helper.geometry.dispose();
  }
}
