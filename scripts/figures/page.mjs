// The gallery's page (loaded by render.mjs in headless Chromium): draws one
// recorded mesh with the app's own surface material, heat palettes and mesh
// view (web/src/viewer/), from a fixed camera, and returns the PNG. No
// animation, no controls: one frame per picture.
import { Color, PerspectiveCamera, Scene, Vector3, WebGLRenderer } from 'three';
import { HEAT_PALETTES, FIXED_HEAT_RANGE } from '/web/src/viewer/heat-palettes.js';
import { MeshView } from '/web/src/viewer/mesh-view.js';

const renderer = new WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(1);
// Lighter than the app's dark viewport: the pictures sit on a white page.
renderer.setClearColor(new Color(0xf4f4f2));
document.body.append(renderer.domElement);

/**
 * picture: {mesh: recorded mesh JSON, width, height, frame: {center, radius},
 * direction, up, flat, wireframe}. Returns the pixels, RGBA top row first, in
 * base64 (render.mjs writes the PNG).
 */
window.renderPicture = (picture) => {
  renderer.setSize(picture.width, picture.height, false);
  const scene = new Scene();
  const view = new MeshView({ canvas: renderer.domElement, scene, requestRender() {} });
  const { positions, triangles, selection, heat, heatKind } = picture.mesh;
  view.setMesh(positions, triangles);
  view.setFlatShading(Boolean(picture.flat));
  view.setWireframe(Boolean(picture.wireframe));
  if (selection) view.showSelection(selection);
  view.setSelectionVisible(Boolean(selection));
  if (heat) {
    view.setHeatPalette(HEAT_PALETTES[heatKind]);
    view.setHeatRange(FIXED_HEAT_RANGE[heatKind]);
    view.showDistortion(heat);
  }
  view.setHeatMapVisible(Boolean(heat));

  const camera = new PerspectiveCamera(30, picture.width / picture.height, 0.001, 1000);
  const center = new Vector3(...picture.frame.center);
  const direction = new Vector3(...picture.direction).normalize();
  // The frame's sphere fits the narrower of the two fields of view.
  const halfFov = (camera.fov * Math.PI) / 360;
  const fit = Math.min(halfFov, Math.atan(Math.tan(halfFov) * camera.aspect));
  const distance = (1.05 * picture.frame.radius) / Math.sin(fit);
  camera.position.copy(center).addScaledVector(direction, distance);
  camera.up.set(...picture.up);
  camera.near = distance / 100;
  camera.far = distance * 100;
  camera.lookAt(center);
  camera.updateProjectionMatrix();
  renderer.render(scene, camera);
  const { width, height } = picture;
  const gl = renderer.getContext();
  const bottomUp = new Uint8Array(width * height * 4);
  gl.readPixels(0, 0, width, height, gl.RGBA, gl.UNSIGNED_BYTE, bottomUp);
  view.geometry.dispose();
  view.material.dispose();
  view.wireframeMaterial.dispose();
  let binary = '';
  for (let y = height - 1; y >= 0; y--) {
    binary += String.fromCharCode(...bottomUp.subarray(y * width * 4, (y + 1) * width * 4));
  }
  return btoa(binary);
};
window.pageReady = true;
