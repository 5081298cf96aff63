// The mesh's material: a ShaderMaterial built from the GLSL in ../../../shaders,
// composed with #include like three.js's own chunks (the overlay and heat-map
// chunks are registered in ShaderChunk under aniso_* names).
import { Color, DoubleSide, ShaderChunk, ShaderMaterial } from 'three';
import distortionHeatmap from '../../../shaders/distortion_heatmap.glsl?raw';
import selectionOverlay from '../../../shaders/selection_overlay.glsl?raw';
import surfaceFragment from '../../../shaders/surface.frag.glsl?raw';
import surfaceVertex from '../../../shaders/surface.vert.glsl?raw';

ShaderChunk.aniso_selection_overlay = selectionOverlay;
ShaderChunk.aniso_distortion_heatmap = distortionHeatmap;

export function createSurfaceMaterial() {
  return new ShaderMaterial({
    // Open meshes (garment panels, scans) show their inside; the fragment
    // shader lights back faces as seen, and picking hits both sides.
    side: DoubleSide,
    vertexShader: surfaceVertex,
    fragmentShader: surfaceFragment,
    uniforms: {
      uBaseColor: { value: new Color(0xc9c4bb) },
      uSelectionColor: { value: new Color(0xff7a1a) },
      uSelectionOpacity: { value: 0.75 },
      uShowSelection: { value: true },
      uShowHeatMap: { value: false },
      uHeatRange: { value: 1.0 },
      uHeatOneSided: { value: false },
      uHeatNeutral: { value: new Color() },
      uHeatShrunk: { value: new Color() },
      uHeatMiddle: { value: new Color() },
      uHeatGrown: { value: new Color() },
    },
  });
}
