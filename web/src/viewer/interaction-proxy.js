// A lighter drawing of the edited mesh while it moves, on CPU rasterisers only.
//
// Why: SwiftShader, llvmpipe and the like (software-rendering.js) pay per
// triangle, on the same few cores the solver needs: a 52k-triangle mesh takes
// 60-190 ms a frame on two cores, so a live preview or an orbit showed 5-8 new
// shapes a second however fast the solver was. While the shape or the camera
// moves, this draws a simplified mesh instead (PROXY_TRIANGLES triangles,
// made off the main thread: worker/display-proxy.js) whose vertices are a
// subset of the mesh's own: each frame gathers their positions and computes
// their normals, and the full mesh's GPU buffers are left alone until it is
// drawn again. The full mesh comes back once nothing has moved for
// SETTLE_MS, and at once when an edit is committed. A GPU draws the full
// mesh all the time.
//
// The canvas's data-detail attribute says what is drawn ('full' or 'proxy'),
// for tests and assistive tools.
import { BufferAttribute, BufferGeometry, DynamicDrawUsage, Mesh } from 'three';
import { rendersInSoftware } from './software-rendering.js';
import { writeVertexNormals } from './vertex-normals.js';

/** Triangles of the moving drawing: a few ms a frame in SwiftShader. */
export const PROXY_TRIANGLES = 6000;
/** A mesh this small is drawn in full even while it moves. */
const MIN_TRIANGLES_FOR_PROXY = 3 * PROXY_TRIANGLES;
/**
 * How long nothing must move before the full mesh is drawn again: longer
 * than a screen drag's preview takes at 26k vertices (~250 ms), so that a
 * drag does not flicker between the two drawings.
 */
const SETTLE_MS = 600;
/** The per-vertex attributes the proxy copies from the full mesh (the surface material's). */
const GATHERED = [['position', 3], ['selectionWeight', 1], ['distortion', 1]];

export class InteractionProxy {
  #viewer;
  #material;
  #simplify;
  #beforeFull;
  #full = null; // {mesh, wireframe}: drawn when settled
  #proxy = null; // {mesh, vertices: the full mesh's index of each proxy vertex}
  #moving = false;
  #settleTimer = 0;
  #generation = 0;
  #startAfter;
  #startNow = null; // starts the waiting simplification at once

  /**
   * simplify(triangles): a promise of the loaded mesh simplified to about
   * that many triangles, {vertices, triangles} (display-proxy.js; null: no
   * proxy). beforeFull(): called before the full mesh is drawn again (its
   * normals may be stale: frames drawn by the proxy skip them).
   * startAfter(): a promise of when to ask for the simplification (the
   * solver's preparation of the new mesh: a select right after a load would
   * otherwise wait for it in the worker), unless the mesh moves first.
   */
  constructor(viewer, material, { simplify = null, beforeFull = () => {}, enabled = rendersInSoftware(), startAfter = () => Promise.resolve() } = {}) {
    this.#viewer = viewer;
    this.#material = material;
    this.#simplify = simplify;
    this.#startAfter = startAfter;
    this.#beforeFull = beforeFull;
    this.enabled = enabled && simplify !== null;
    this.#syncDataset();
  }

  /**
   * A new mesh (`geometry`, drawn by `mesh` and its wireframe overlay
   * `wireframe`): the old proxy goes, and a new one is built in the
   * background when this mesh is worth it. Resolves when that is done.
   */
  setMesh(geometry, mesh, wireframe) {
    this.#dropProxy();
    this.#full = { mesh, wireframe };
    if (!this.enabled || geometry.index.count / 3 < MIN_TRIANGLES_FOR_PROXY) return Promise.resolve();
    const generation = ++this.#generation;
    const started = new Promise((resolve) => {
      this.#startNow = resolve;
      this.#startAfter().then(resolve, resolve);
    });
    return started.then(() => (generation === this.#generation ? this.#simplify(PROXY_TRIANGLES) : null)).then((simplified) => {
      if (generation !== this.#generation) return; // another mesh came since
      const { vertices, triangles } = simplified;
      const proxyGeometry = new BufferGeometry();
      for (const [name, size] of GATHERED) {
        proxyGeometry.setAttribute(name, new BufferAttribute(new Float32Array(vertices.length * size), size).setUsage(DynamicDrawUsage));
      }
      proxyGeometry.setAttribute('normal', new BufferAttribute(new Float32Array(vertices.length * 3), 3).setUsage(DynamicDrawUsage));
      proxyGeometry.setIndex(new BufferAttribute(triangles, 1));
      this.#proxy = { mesh: new Mesh(proxyGeometry, this.#material), vertices };
      this.#proxy.mesh.frustumCulled = false;
      this.#proxy.mesh.visible = false;
      for (const [name] of GATHERED) this.showAttribute(name, geometry.getAttribute(name).array);
      // Its normals too: an orbit moves no vertex, and draws the proxy as it is.
      this.showPositions(geometry.getAttribute('position').array);
      this.#viewer.scene.add(this.#proxy.mesh);
      if (this.#moving) this.#show();
    }, () => {
      // Without a simplification (the mesh was replaced meanwhile, or the
      // solver restarted) the full mesh is drawn throughout.
    });
  }

  /** Something moved (a live preview's shape, the camera): the light drawing until it settles. */
  moved() {
    if (!this.#full || !this.enabled) return;
    this.#startNow?.();
    this.#moving = true;
    clearTimeout(this.#settleTimer);
    this.#settleTimer = setTimeout(() => this.settle(), SETTLE_MS);
    this.#show();
  }

  /** Motion ended (a committed edit, a released orbit): the full mesh at once. */
  settle() {
    clearTimeout(this.#settleTimer);
    const wasDrawing = this.drawing;
    this.#moving = false;
    if (wasDrawing) this.#show();
  }

  /** Whether the proxy is what is drawn now. */
  get drawing() {
    return this.#moving && this.#proxy !== null;
  }

  /** The triangle count drawn now. */
  get drawnTriangles() {
    const drawn = this.drawing ? this.#proxy.mesh : this.#full?.mesh;
    return drawn ? drawn.geometry.index.count / 3 : 0;
  }

  /** New full-mesh positions (3 per vertex): the proxy's vertices follow, with their normals. */
  showPositions(positions) {
    if (!this.#proxy) return;
    this.showAttribute('position', positions);
    const geometry = this.#proxy.mesh.geometry;
    const normals = geometry.getAttribute('normal');
    writeVertexNormals(geometry.getAttribute('position').array, geometry.index.array, normals.array);
    normals.needsUpdate = true;
  }

  /** A full-mesh per-vertex attribute of GATHERED changed: the proxy's copy follows. */
  showAttribute(name, values) {
    if (!this.#proxy) return;
    const attribute = this.#proxy.mesh.geometry.getAttribute(name);
    const { array, itemSize } = attribute;
    const { vertices } = this.#proxy;
    for (let p = 0; p < vertices.length; p++) {
      for (let k = 0, from = itemSize * vertices[p], to = itemSize * p; k < itemSize; k++) array[to + k] = values[from + k];
    }
    attribute.needsUpdate = true;
  }

  #show() {
    if (!this.#full) return;
    const proxy = this.drawing;
    if (!proxy) this.#beforeFull();
    if (this.#proxy) this.#proxy.mesh.visible = proxy;
    this.#full.mesh.visible = !proxy;
    // The wireframe is the full mesh's: it would be wrong over the proxy.
    this.#full.wireframe.visible = !proxy;
    this.#syncDataset();
    this.#viewer.requestRender();
  }

  #dropProxy() {
    this.#generation++;
    if (!this.#proxy) return;
    this.#viewer.scene.remove(this.#proxy.mesh);
    this.#proxy.mesh.geometry.dispose();
    this.#proxy = null;
  }

  dispose() {
    clearTimeout(this.#settleTimer);
    this.#dropProxy();
    this.#full = null;
  }

  #syncDataset() {
    this.#viewer.canvas.dataset.detail = this.drawing ? 'proxy' : 'full';
  }
}
