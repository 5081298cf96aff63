// Direction glyphs on the surface: instanced shapes (one base shape, one
// instance per sampled vertex), drawn with shaders/direction_glyph.*: line
// strokes for a direction field, flat arrows with heads for placed arrows.
// A field is thinned to one glyph per cell of a grid of `spacing` (the
// caller sets it from the screen, see direction-display.js), then to at most
// `maxGlyphs`, so a 200k-vertex mesh shows a readable field and uploads little.
import {
  BufferAttribute,
  Color,
  DoubleSide,
  InstancedBufferAttribute,
  InstancedBufferGeometry,
  LineSegments,
  Mesh,
  ShaderMaterial,
} from 'three';
import glyphFragment from '../../../shaders/direction_glyph.frag.glsl?raw';
import glyphVertex from '../../../shaders/direction_glyph.vert.glsl?raw';

const MAX_GLYPHS = 2000;

// (along, across) in glyph lengths.
const LINE_SHAPE = [[-0.5, 0], [0.5, 0]];
const SHAFT = 0.05, HEAD_START = 0.65, HEAD = 0.2;
const ARROW_SHAPE = [
  [0, -SHAFT], [HEAD_START, -SHAFT], [HEAD_START, SHAFT],
  [0, -SHAFT], [HEAD_START, SHAFT], [0, SHAFT],
  [HEAD_START, -HEAD], [1, 0], [HEAD_START, HEAD],
];

export class DirectionGlyphs {
  /** kind 'line' (a field) or 'arrow' (placed arrows, drawn from the vertex along the direction). */
  constructor(viewer, { color = 0x7fe3ff, maxGlyphs = MAX_GLYPHS, kind = 'line' } = {}) {
    this.viewer = viewer;
    this.maxGlyphs = maxGlyphs;
    this.kind = kind;
    const shape = kind === 'arrow' ? ARROW_SHAPE : LINE_SHAPE;
    const geometry = new InstancedBufferGeometry();
    // three.js needs a position attribute to draw; the shader ignores it.
    geometry.setAttribute('position', new BufferAttribute(new Float32Array(shape.length * 3), 3));
    geometry.setAttribute('glyphShape', new BufferAttribute(new Float32Array(shape.flat()), 2));
    geometry.setAttribute('glyphOrigin', new InstancedBufferAttribute(new Float32Array(maxGlyphs * 3), 3));
    geometry.setAttribute('glyphDirection', new InstancedBufferAttribute(new Float32Array(maxGlyphs * 3), 3));
    geometry.setAttribute('glyphNormal', new InstancedBufferAttribute(new Float32Array(maxGlyphs * 3), 3));
    geometry.setAttribute('glyphWeight', new InstancedBufferAttribute(new Float32Array(maxGlyphs), 1));
    geometry.instanceCount = 0;
    this.geometry = geometry;
    this.material = new ShaderMaterial({
      vertexShader: glyphVertex,
      fragmentShader: glyphFragment,
      uniforms: {
        uGlyphLength: { value: 0.05 },
        uGlyphColor: { value: new Color(color) },
        uEndFade: { value: kind === 'arrow' ? 0 : 0.55 },
      },
      side: DoubleSide,
      depthTest: true,
    });
    this.object = kind === 'arrow' ? new Mesh(geometry, this.material) : new LineSegments(geometry, this.material);
    this.object.frustumCulled = false; // instances are placed in the shader
    this.object.renderOrder = 2;
    this.object.visible = false;
    this.count = 0;
    viewer.scene.add(this.object);
  }

  /**
   * @param {object} field
   * @param {Float32Array} field.directions  unit direction per vertex (#V*3); zero = none
   * @param {Float32Array} field.positions   #V*3
   * @param {Float32Array} field.normals     #V*3, to lift glyphs off the surface
   * @param {Float32Array|null} field.weights selection weight per vertex; null = all
   * @param {number} field.length            glyph length in model units
   * @param {number} [field.spacing]         at most one glyph per grid cell of this size
   * @param {number[]} [field.vertices]      draw exactly these vertices (arrows)
   * @returns {number} the glyphs drawn
   */
  show({ directions, positions, normals, weights, length, spacing = 0, vertices = null }) {
    let candidates = vertices ?? candidateVertices(weights, positions.length / 3);
    if (!vertices && spacing > 0) candidates = onePerCell(candidates, positions, spacing);
    const stride = Math.max(1, Math.ceil(candidates.length / this.maxGlyphs));
    const origin = this.geometry.getAttribute('glyphOrigin');
    const direction = this.geometry.getAttribute('glyphDirection');
    const normal = this.geometry.getAttribute('glyphNormal');
    const weight = this.geometry.getAttribute('glyphWeight');
    const lift = length * 0.08;
    let count = 0;
    for (let k = 0; k < candidates.length && count < this.maxGlyphs; k += stride) {
      const v = candidates[k];
      const dx = directions[3 * v], dy = directions[3 * v + 1], dz = directions[3 * v + 2];
      if (dx === 0 && dy === 0 && dz === 0) continue;
      for (let axis = 0; axis < 3; axis++) {
        origin.array[3 * count + axis] = positions[3 * v + axis] + normals[3 * v + axis] * lift;
        normal.array[3 * count + axis] = normals[3 * v + axis];
      }
      direction.array[3 * count] = dx;
      direction.array[3 * count + 1] = dy;
      direction.array[3 * count + 2] = dz;
      weight.array[count] = weights ? weights[v] : 1;
      count++;
    }
    origin.needsUpdate = direction.needsUpdate = normal.needsUpdate = weight.needsUpdate = true;
    this.geometry.instanceCount = count;
    this.material.uniforms.uGlyphLength.value = length;
    this.object.visible = count > 0;
    this.count = count;
    this.viewer.requestRender();
    return count;
  }

  hide() {
    this.count = 0;
    if (!this.object.visible) return;
    this.object.visible = false;
    this.viewer.requestRender();
  }
}

function candidateVertices(weights, vertexCount) {
  const list = [];
  for (let v = 0; v < vertexCount; v++) if (!weights || weights[v] > 0) list.push(v);
  if (list.length === 0) for (let v = 0; v < vertexCount; v++) list.push(v);
  return list;
}

// The first candidate in each cell of a grid of `spacing`: glyphs spread
// evenly over the surface however the mesh's vertices are spread.
function onePerCell(candidates, positions, spacing) {
  const taken = new Set();
  const kept = [];
  for (const v of candidates) {
    const key = `${Math.floor(positions[3 * v] / spacing)},${Math.floor(positions[3 * v + 1] / spacing)},${Math.floor(positions[3 * v + 2] / spacing)}`;
    if (taken.has(key)) continue;
    taken.add(key);
    kept.push(v);
  }
  return kept;
}
