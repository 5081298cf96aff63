// Direction glyphs: one instanced line segment per sampled vertex. The base
// geometry is a single segment with `glyphEnd` = -1 and +1; each instance
// brings its surface point, unit direction and weight. Directions are line
// fields (sign does not matter), so the segment is centred on the point.
attribute float glyphEnd;
attribute vec3 glyphOrigin;
attribute vec3 glyphDirection;
attribute float glyphWeight;

uniform float uGlyphLength;

varying float vGlyphWeight;
varying float vGlyphEnd;

void main() {
  vec3 world = glyphOrigin + glyphDirection * (glyphEnd * 0.5 * uGlyphLength * (0.5 + 0.5 * glyphWeight));
  vGlyphWeight = glyphWeight;
  vGlyphEnd = glyphEnd;
  gl_Position = projectionMatrix * modelViewMatrix * vec4(world, 1.0);
}
