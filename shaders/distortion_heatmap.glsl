// Distortion heat map (chunk: aniso_distortion_heatmap).
// The input is log2 of a ratio against the loaded mesh (area ratio, or the
// largest stretch), so growing and shrinking by the same factor get the same
// strength: uHeatShrunk = shrunk, uHeatNeutral = unchanged, uHeatGrown =
// grown. uHeatRange is the value that saturates the colour (1.0 = twice /
// half). A flattening's compression error (|achieved / wanted - 1|, never
// negative) is one-sided: neutral - uHeatMiddle - grown, with uHeatRange =
// the error shown at full colour. The colours are the palettes of
// web/src/viewer/heat-palettes.js, which mixes them the same way for the legend.
uniform float uHeatRange;
uniform bool uHeatOneSided;
uniform vec3 uHeatNeutral;
uniform vec3 uHeatShrunk;
uniform vec3 uHeatMiddle;
uniform vec3 uHeatGrown;

vec3 distortionColor(float value) {
  if (uHeatOneSided) {
    float s = clamp(value / uHeatRange, 0.0, 1.0);
    return s < 0.5 ? mix(uHeatNeutral, uHeatMiddle, 2.0 * s) : mix(uHeatMiddle, uHeatGrown, 2.0 * s - 1.0);
  }
  float t = clamp(value / uHeatRange, -1.0, 1.0);
  // sqrt makes small distortions visible without saturating large ones.
  float strength = sqrt(abs(t));
  return t >= 0.0 ? mix(uHeatNeutral, uHeatGrown, strength) : mix(uHeatNeutral, uHeatShrunk, strength);
}
