// Surface shading: a headlight (the light sits at the camera, so every visible
// side is lit while orbiting) with a soft hemisphere ambient, then either the
// distortion heat map or the base colour, then the selection overlay.
#include <aniso_selection_overlay>
#include <aniso_distortion_heatmap>

uniform vec3 uBaseColor;
uniform bool uShowHeatMap;
uniform bool uShowSelection;

varying vec3 vViewNormal;
varying vec3 vViewPosition;
varying float vSelectionWeight;
varying float vDistortion;

void main() {
#ifdef FLAT_SHADED
  // Flat shading (material.flatShading): one normal per triangle, from the
  // screen-space derivatives of the position, so CAD edges stay sharp.
  vec3 normal = normalize(cross(dFdx(vViewPosition), dFdy(vViewPosition)));
  if (dot(normal, vViewNormal) < 0.0) normal = -normal;
#else
  vec3 normal = normalize(vViewNormal);
#endif
  // Back faces (open meshes, flipped faces) are lit as seen, not black.
  if (!gl_FrontFacing) normal = -normal;
  vec3 toEye = normalize(-vViewPosition);
  float diffuse = max(dot(normal, toEye), 0.0);
  vec3 halfway = normalize(toEye + vec3(0.3, 0.5, 1.0));
  float specular = pow(max(dot(normal, halfway), 0.0), 48.0) * 0.18;
  float ambient = 0.28 + 0.12 * normal.y;

  vec3 albedo = uShowHeatMap ? distortionColor(vDistortion) : uBaseColor;
  vec3 shaded = albedo * (ambient + 0.72 * diffuse) + vec3(specular);
  if (uShowSelection) shaded = applySelectionOverlay(shaded, vSelectionWeight);
  gl_FragColor = vec4(shaded, 1.0);
}
