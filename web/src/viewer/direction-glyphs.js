// Direction glyphs on the surface: instanced line segments (one base segment,
// one instance per sampled vertex), drawn with shaders/direction_glyph.*.
// At most MAX_GLYPHS vertices are sampled, evenly through the vertex list, so
// a 200k-vertex mesh shows a readable field and uploads little.
import {
  BufferAttribute,
  Color,
  InstancedBufferAttribute,
  InstancedBufferGeometry,
  LineSegments,
  ShaderMaterial,
} from 'three';
import glyphFragment from '../../../shaders/direction_glyph.frag.glsl?raw';
import glyphVertex from '../../../shaders/direction_glyph.vert.glsl?raw';

const MAX_GLYPHS = 2000;

export class DirectionGlyphs {
  constructor(viewer, { color = 0x7fe3ff, maxGlyphs = MAX_GLYPHS } = {}) {
    this.viewer = viewer;
    this.maxGlyphs = maxGlyphs;
    const geometry = new InstancedBufferGeometry();
    // three.js needs a position attribute to draw; the shader ignores it.
    geometry.setAttribute('position', new BufferAttribute(new Float32Array(6), 3));
    geometry.setAttribute('glyphEnd', new BufferAttribute(new Float32Array([-1, 1]), 1));
    geometry.setAttribute('glyphOrigin', new InstancedBufferAttribute(new Float32Array(maxGlyphs * 3), 3));
    geometry.setAttribute('glyphDirection', new InstancedBufferAttribute(new Float32Array(maxGlyphs * 3), 3));
    geometry.setAttribute('glyphWeight', new InstancedBufferAttribute(new Float32Array(maxGlyphs), 1));
    geometry.instanceCount = 0;
    this.geometry = geometry;
    this.material = new ShaderMaterial({
      vertexShader: glyphVertex,
      fragmentShader: glyphFragment,
      uniforms: { uGlyphLength: { value: 0.05 }, uGlyphColor: { value: new Color(color) } },
      depthTest: true,
    });
    this.lines = new LineSegments(geometry, this.material);
    this.lines.frustumCulled = false; // instances are placed in the shader
    this.lines.renderOrder = 1;
    viewer.scene.add(this.lines);
  }

  /**
   * @param {object} field
   * @param {Float32Array} field.directions  unit direction per vertex (#V*3); zero = none
   * @param {Float32Array} field.positions   #V*3
   * @param {Float32Array} field.normals     #V*3, to lift glyphs off the surface
   * @param {Float32Array|null} field.weights selection weight per vertex; null = all
   * @param {number} field.length            glyph length in model units
   */
  show({ directions, positions, normals, weights, length, vertices = null }) {
    const candidates = vertices ?? candidateVertices(weights, positions.length / 3);
    const stride = Math.max(1, Math.ceil(candidates.length / this.maxGlyphs));
    const origin = this.geometry.getAttribute('glyphOrigin');
    const direction = this.geometry.getAttribute('glyphDirection');
    const weight = this.geometry.getAttribute('glyphWeight');
    const lift = length * 0.08;
    let count = 0;
    for (let k = 0; k < candidates.length && count < this.maxGlyphs; k += stride) {
      const v = candidates[k];
      const dx = directions[3 * v], dy = directions[3 * v + 1], dz = directions[3 * v + 2];
      if (dx === 0 && dy === 0 && dz === 0) continue;
      for (let axis = 0; axis < 3; axis++) {
        origin.array[3 * count + axis] = positions[3 * v + axis] + normals[3 * v + axis] * lift;
      }
      direction.array[3 * count] = dx;
      direction.array[3 * count + 1] = dy;
      direction.array[3 * count + 2] = dz;
      weight.array[count] = weights ? weights[v] : 1;
      count++;
    }
    origin.needsUpdate = direction.needsUpdate = weight.needsUpdate = true;
    this.geometry.instanceCount = count;
    this.material.uniforms.uGlyphLength.value = length;
    this.lines.visible = count > 0;
    this.viewer.requestRender();
    return count;
  }

  hide() {
    if (!this.lines.visible) return;
    this.lines.visible = false;
    this.viewer.requestRender();
  }
}

function candidateVertices(weights, vertexCount) {
  const list = [];
  for (let v = 0; v < vertexCount; v++) if (!weights || weights[v] > 0) list.push(v);
  if (list.length === 0) for (let v = 0; v < vertexCount; v++) list.push(v);
  return list;
}
