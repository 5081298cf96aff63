// Direction glyphs: dark at the ends, bright in the middle, so dense fields
// read as strokes rather than a solid mesh of lines.
uniform vec3 uGlyphColor;

varying float vGlyphWeight;
varying float vGlyphEnd;

void main() {
  float fade = 1.0 - 0.55 * abs(vGlyphEnd);
  gl_FragColor = vec4(uGlyphColor * fade, 1.0);
}
