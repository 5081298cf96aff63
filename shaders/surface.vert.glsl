// Surface of the edited mesh: passes the view-space normal and position for a
// headlight, plus the per-vertex selection weight and distortion value.
attribute float selectionWeight;
attribute float distortion;

varying vec3 vViewNormal;
varying vec3 vViewPosition;
varying float vSelectionWeight;
varying float vDistortion;

void main() {
  vec4 viewPosition = modelViewMatrix * vec4(position, 1.0);
  vViewPosition = viewPosition.xyz;
  vViewNormal = normalize(normalMatrix * normal);
  vSelectionWeight = selectionWeight;
  vDistortion = distortion;
  gl_Position = projectionMatrix * viewPosition;
}
