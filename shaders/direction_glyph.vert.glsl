// Direction glyphs: one instanced shape per sampled vertex. The base
// geometry's `glyphShape` is (along, across) in glyph lengths: a centred line
// segment for a field (directions are line fields, sign does not matter), or
// a flat arrow (shaft and head, in the tangent plane) for a placed arrow.
// Each instance brings its surface point, unit direction, normal and weight.
attribute vec2 glyphShape;
attribute vec3 glyphOrigin;
attribute vec3 glyphDirection;
attribute vec3 glyphNormal;
attribute float glyphWeight;

uniform float uGlyphLength;

varying float vGlyphWeight;
varying float vGlyphEnd;

void main() {
  vec3 side = cross(glyphNormal, glyphDirection);
  float sideLength = length(side);
  side = sideLength > 1e-8 ? side / sideLength : vec3(0.0);
  float size = uGlyphLength * (0.5 + 0.5 * glyphWeight);
  vec3 world = glyphOrigin + (glyphDirection * glyphShape.x + side * glyphShape.y) * size;
  vGlyphWeight = glyphWeight;
  vGlyphEnd = 2.0 * glyphShape.x;
  gl_Position = projectionMatrix * modelViewMatrix * vec4(world, 1.0);
}
