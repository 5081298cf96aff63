// Distortion heat map (chunk: aniso_distortion_heatmap).
// The input is log2 of a ratio against the loaded mesh (area ratio, or the
// largest stretch), so growing and shrinking by the same factor get the same
// strength: blue = shrunk, white = unchanged, red = grown. uHeatRange is the
// value that saturates the colour (1.0 = twice / half). A flattening's
// compression error (|achieved / wanted - 1|, never negative) uses the red
// half only, with uHeatRange = the error shown at full red.
uniform float uHeatRange;

vec3 distortionColor(float log2Ratio) {
  float t = clamp(log2Ratio / uHeatRange, -1.0, 1.0);
  vec3 neutral = vec3(0.92, 0.92, 0.90);
  vec3 grown = vec3(0.85, 0.18, 0.12);
  vec3 shrunk = vec3(0.14, 0.35, 0.85);
  // sqrt makes small distortions visible without saturating large ones.
  float strength = sqrt(abs(t));
  return t >= 0.0 ? mix(neutral, grown, strength) : mix(neutral, shrunk, strength);
}
