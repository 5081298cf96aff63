// Direction glyphs: a field's strokes are dark at the ends and bright in the
// middle (uEndFade), so dense fields read as strokes rather than a solid mesh
// of lines; arrows are solid.
uniform vec3 uGlyphColor;
uniform float uEndFade;

varying float vGlyphWeight;
varying float vGlyphEnd;

void main() {
  float fade = 1.0 - uEndFade * abs(vGlyphEnd);
  gl_FragColor = vec4(uGlyphColor * fade, 1.0);
}
