// Selection-weight overlay (chunk: aniso_selection_overlay).
// Tints the shaded colour towards the selection colour by the vertex's
// selection weight, and draws thin iso-lines at weights 0.25/0.5/0.75 so a
// soft falloff reads as a gradient with visible steps rather than a blur.
uniform vec3 uSelectionColor;
uniform float uSelectionOpacity;

vec3 applySelectionOverlay(vec3 shaded, float weight) {
  if (weight <= 0.0) return shaded;
  vec3 tinted = mix(shaded, uSelectionColor * (0.35 + 0.65 * length(shaded) / 1.732), uSelectionOpacity * weight);
  // fwidth keeps the iso-lines one pixel wide whatever the zoom.
  float band = fract(weight * 4.0);
  float lineWidth = fwidth(weight * 4.0);
  float isoLine = 1.0 - smoothstep(0.0, lineWidth * 1.5, min(band, 1.0 - band));
  return mix(tinted, uSelectionColor, isoLine * 0.6 * step(weight, 0.999));
}
