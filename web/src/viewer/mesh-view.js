// The edited mesh on screen: a BufferGeometry with positions, normals,
// selection weights and distortion values, drawn with the surface material.
// The geometry keeps its own copies of the arrays (the editor's arrays are
// immutable and shared with the undo history).
import { BufferAttribute, BufferGeometry, DynamicDrawUsage, Mesh } from 'three';
import { createSurfaceMaterial } from './surface-material.js';

export class MeshView {
  /** @type {BufferGeometry|null} */
  geometry = null;
  mesh = null;

  constructor(viewer) {
    this.viewer = viewer;
    this.material = createSurfaceMaterial();
  }

  setMesh(positions, triangles) {
    if (this.mesh) {
      this.viewer.scene.remove(this.mesh);
      this.geometry.dispose();
    }
    const vertexCount = positions.length / 3;
    const geometry = new BufferGeometry();
    geometry.setAttribute('position', dynamic(new BufferAttribute(new Float32Array(positions), 3)));
    geometry.setIndex(new BufferAttribute(new Uint32Array(triangles), 1));
    geometry.setAttribute('selectionWeight', dynamic(new BufferAttribute(new Float32Array(vertexCount), 1)));
    geometry.setAttribute('distortion', dynamic(new BufferAttribute(new Float32Array(vertexCount), 1)));
    geometry.computeVertexNormals();
    geometry.getAttribute('normal').setUsage(DynamicDrawUsage);
    geometry.computeBoundingSphere();
    this.geometry = geometry;
    this.mesh = new Mesh(geometry, this.material);
    this.viewer.scene.add(this.mesh);
    this.viewer.requestRender();
  }

  showPositions(positions) {
    const attribute = this.geometry.getAttribute('position');
    attribute.array.set(positions);
    attribute.needsUpdate = true;
    this.geometry.computeVertexNormals();
    this.geometry.computeBoundingSphere();
    this.viewer.requestRender();
  }

  showSelection(weights) {
    const attribute = this.geometry.getAttribute('selectionWeight');
    attribute.array.set(weights);
    attribute.needsUpdate = true;
    this.viewer.requestRender();
  }

  showDistortion(values) {
    const attribute = this.geometry.getAttribute('distortion');
    attribute.array.set(values);
    attribute.needsUpdate = true;
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

  setSelectionVisible(visible) {
    this.material.uniforms.uShowSelection.value = visible;
    this.viewer.requestRender();
  }

  /** The displayed positions (a live preview included). */
  get displayedPositions() {
    return this.geometry.getAttribute('position').array;
  }

  get normals() {
    return this.geometry.getAttribute('normal').array;
  }
}

function dynamic(attribute) {
  attribute.setUsage(DynamicDrawUsage);
  return attribute;
}
