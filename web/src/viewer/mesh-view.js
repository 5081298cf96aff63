// The edited mesh on screen: a BufferGeometry with positions, normals,
// selection weights and distortion values, drawn with the surface material.
// The geometry keeps its own copy of the positions (the editor's arrays are
// immutable and shared with the undo history); the index, never written, is
// the editor's triangles, and the normals are the worker's, taken over. A big
// mesh is drawn once its buffers are on the GPU (staged-upload.js). Flat
// shading and a wireframe overlay are display options; the canvas's
// data-flat-shading and data-wireframe attributes say what the materials
// draw (for tests and assistive tools).
import { BufferAttribute, BufferGeometry, DynamicDrawUsage, Mesh, MeshBasicMaterial } from 'three';
import { createSurfaceMaterial } from './surface-material.js';
import { writeVertexNormals } from './vertex-normals.js';
import { InteractionProxy } from './interaction-proxy.js';
import { StagedUpload } from './staged-upload.js';

export class MeshView {
  /** @type {BufferGeometry|null} */
  geometry = null;
  mesh = null;
  /** Resolves when the last mesh given to setMesh is drawn (its buffers uploaded: staged-upload.js). */
  shown = Promise.resolve();
  /** Positions changed since the normals were computed (a proxy frame skips them). */
  #normalsStale = false;
  #upload;
  #resolveShown = null;

  /** simplify, startAfter: InteractionProxy's (the solver worker's simplification of the loaded mesh, and when). */
  constructor(viewer, { simplify = null, startAfter } = {}) {
    this.viewer = viewer;
    this.material = createSurfaceMaterial();
    this.material.flatShading = false;
    // The surface is pushed back a little so the wireframe's lines win the depth test.
    this.material.polygonOffset = true;
    this.material.polygonOffsetFactor = 1;
    this.material.polygonOffsetUnits = 1;
    this.wireframeMaterial = new MeshBasicMaterial({ color: 0x22262c, wireframe: true, transparent: true, opacity: 0.45 });
    this.wireframeMaterial.visible = false;
    this.wireframe = null;
    this.#upload = new StagedUpload(viewer, this.material);
    this.proxy = new InteractionProxy(viewer, this.material, { simplify, startAfter, beforeFull: () => this.#refreshNormals() });
    // An orbit on a CPU rasteriser draws the light mesh too (interaction-proxy.js).
    let orbiting = false;
    viewer.controls.addEventListener('start', () => {
      orbiting = true;
      this.proxy.moved();
    });
    viewer.controls.addEventListener('change', () => orbiting && this.proxy.moved());
    viewer.controls.addEventListener('end', () => {
      orbiting = false;
      this.proxy.settle();
    });
    this.#syncDataset();
  }

  setFlatShading(flat) {
    if (this.material.flatShading === flat) return;
    this.material.flatShading = flat;
    this.material.needsUpdate = true; // a different program (FLAT_SHADED)
    this.#syncDataset();
    this.viewer.requestRender();
  }

  /** false: the file's look is drawn instead (gltf-display.js); the surface stays for picking. */
  setSurfaceVisible(visible) {
    if (this.material.visible === visible) return;
    this.material.visible = visible;
    this.viewer.requestRender();
  }

  setWireframe(visible) {
    this.wireframeMaterial.visible = visible;
    this.#syncDataset();
    this.viewer.requestRender();
  }

  #syncDataset() {
    const canvas = this.viewer.canvas.dataset;
    canvas.flatShading = String(this.material.flatShading);
    canvas.wireframe = String(this.wireframeMaterial.visible && this.wireframe !== null);
  }

  /** normals: of `positions`, computed by the solver worker (worker/mesh-display.js); the view takes the array over. */
  setMesh(positions, triangles, normals) {
    this.#upload.cancel();
    if (this.mesh) {
      this.viewer.scene.remove(this.mesh, this.wireframe);
      this.geometry.dispose();
    }
    const vertexCount = positions.length / 3;
    const geometry = new BufferGeometry();
    geometry.setAttribute('position', dynamic(new BufferAttribute(new Float32Array(positions), 3)));
    geometry.setIndex(new BufferAttribute(triangles, 1));
    geometry.setAttribute('selectionWeight', dynamic(new BufferAttribute(new Float32Array(vertexCount), 1)));
    geometry.setAttribute('distortion', dynamic(new BufferAttribute(new Float32Array(vertexCount), 1)));
    geometry.setAttribute('normal', dynamic(new BufferAttribute(normals, 3)));
    // No bounding sphere: the renderer computes it when it first draws the
    // mesh (as after every new shape), not in this task (36 ms at 800k vertices).
    this.geometry = geometry;
    this.mesh = new Mesh(geometry, this.material);
    this.wireframe = new Mesh(geometry, this.wireframeMaterial);
    // The edited mesh is what the camera is framed on: culling it would only
    // cost a bounding sphere per new shape (every frame of a live preview).
    this.mesh.frustumCulled = false;
    this.wireframe.frustumCulled = false;
    this.wireframe.renderOrder = 1;
    const { mesh, wireframe } = this;
    // A mesh replaced before it was drawn will not be: nothing waits for it.
    this.#resolveShown?.();
    this.shown = new Promise((resolve) => {
      this.#resolveShown = resolve;
      this.#upload.upload(geometry, () => {
        this.viewer.scene.add(mesh, wireframe);
        this.viewer.requestRender();
        resolve();
      });
    });
    this.proxy.setMesh(geometry, this.mesh, this.wireframe);
    this.#syncDataset();
    this.viewer.requestRender();
  }

  /** {live: true}: a preview frame while something is dragged (drawn light on a CPU rasteriser). */
  showPositions(positions, { live = false } = {}) {
    const attribute = this.geometry.getAttribute('position');
    attribute.array.set(positions);
    attribute.needsUpdate = true;
    this.#normalsStale = true;
    // Stale: computed again by whatever asks for it (the views are never
    // culled, and picking has its own bounding volumes).
    this.geometry.boundingSphere = null;
    this.geometry.boundingBox = null;
    if (live) this.proxy.moved();
    else this.proxy.settle();
    // The full mesh's normals wait while the proxy is drawn (beforeFull).
    if (this.proxy.drawing) this.proxy.showPositions(attribute.array);
    else this.#refreshNormals();
    this.viewer.requestRender();
  }

  #refreshNormals() {
    if (!this.#normalsStale) return;
    this.#normalsStale = false;
    const normals = this.geometry.getAttribute('normal');
    writeVertexNormals(this.geometry.getAttribute('position').array, this.geometry.index.array, normals.array);
    normals.needsUpdate = true;
  }

  showSelection(weights) {
    const attribute = this.geometry.getAttribute('selectionWeight');
    attribute.array.set(weights);
    attribute.needsUpdate = true;
    this.proxy.showAttribute('selectionWeight', attribute.array);
    this.viewer.requestRender();
  }

  showDistortion(values) {
    const attribute = this.geometry.getAttribute('distortion');
    attribute.array.set(values);
    attribute.needsUpdate = true;
    this.proxy.showAttribute('distortion', attribute.array);
    this.viewer.requestRender();
  }

  setHeatMapVisible(visible) {
    this.material.uniforms.uShowHeatMap.value = visible;
    // Over the heat map the selection keeps only a light tint and its iso-lines.
    this.material.uniforms.uSelectionOpacity.value = visible ? 0.2 : 0.75;
    this.viewer.requestRender();
  }

  /** The value drawn at full heat-map colour. */
  setHeatRange(range) {
    this.material.uniforms.uHeatRange.value = range;
    this.viewer.requestRender();
  }

  /** A palette of heat-palettes.js. */
  setHeatPalette(palette) {
    const uniforms = this.material.uniforms;
    uniforms.uHeatOneSided.value = palette.oneSided;
    for (const [uniform, key] of [['uHeatNeutral', 'neutral'], ['uHeatShrunk', 'shrunk'], ['uHeatMiddle', 'middle'], ['uHeatGrown', 'grown']]) {
      const rgb = palette[key] ?? palette.neutral;
      uniforms[uniform].value.setRGB(rgb[0] / 255, rgb[1] / 255, rgb[2] / 255);
    }
    this.viewer.requestRender();
  }

  setSelectionVisible(visible) {
    this.material.uniforms.uShowSelection.value = visible;
    this.viewer.requestRender();
  }

  /** The displayed positions (a live preview included). */
  get displayedPositions() {
    return this.geometry.getAttribute('position').array;
  }

  get normals() {
    this.#refreshNormals();
    return this.geometry.getAttribute('normal').array;
  }
}

function dynamic(attribute) {
  attribute.setUsage(DynamicDrawUsage);
  return attribute;
}
