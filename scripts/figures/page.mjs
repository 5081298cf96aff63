// The gallery's page (loaded by render.mjs in headless Chromium): draws one
// recorded mesh with the app's own surface material, heat palettes and mesh
// view (web/src/viewer/), from a fixed camera, and returns the PNG. No
// animation, no controls: one frame per picture.
import { Color, EventDispatcher, PerspectiveCamera, Scene, Vector3, WebGLRenderer } from 'three';
import { HEAT_PALETTES, FIXED_HEAT_RANGE } from '/web/src/viewer/heat-palettes.js';
import { MeshView } from '/web/src/viewer/mesh-view.js';
import { writeVertexNormals } from '/web/src/viewer/vertex-normals.js';

const renderer = new WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(1);
// Lighter than the app's dark viewport: the pictures sit on a white page.
renderer.setClearColor(new Color(0xf4f4f2));
document.body.append(renderer.domElement);

// A line drawn on the surface (a twist's meridian): blue; its neutral is
// replaced by the surface's base colour below.
const MARKER = { oneSided: true, neutral: [0, 0, 0], middle: [60, 110, 210], grown: [30, 90, 200] };

/**
 * picture: {mesh: recorded mesh JSON, width, height, frame: {lo, hi} (a box to fit),
 * direction, up, flat, wireframe}. Returns the pixels, RGBA top row first, in
 * base64 (render.mjs writes the PNG).
 */
window.renderPicture = (picture) => {
  renderer.setSize(picture.width, picture.height, false);
  const scene = new Scene();
  // The viewer's part MeshView uses: no orbit controls (an event target that
  // never fires) and no frames (every figure mesh uploads in one step).
  const viewer = { canvas: renderer.domElement, scene, controls: new EventDispatcher(), requestRender() {}, on: () => () => {} };
  const view = new MeshView(viewer);
  const { selection, heat, heatKind } = picture.mesh;
  // The typed arrays MeshView takes (the app's come from the solver worker).
  const positions = new Float32Array(picture.mesh.positions);
  const triangles = new Uint32Array(picture.mesh.triangles);
  const normals = new Float32Array(positions.length);
  writeVertexNormals(positions, triangles, normals);
  view.setMesh(positions, triangles, normals);
  view.setFlatShading(Boolean(picture.flat));
  view.setWireframe(Boolean(picture.wireframe));
  if (selection) view.showSelection(selection);
  view.setSelectionVisible(Boolean(selection));
  if (heat) {
    view.setHeatPalette(heatKind === 'marker' ? MARKER : HEAT_PALETTES[heatKind]);
    // Off the line, the marker shows the surface's own colour.
    if (heatKind === 'marker') view.material.uniforms.uHeatNeutral.value.copy(view.material.uniforms.uBaseColor.value);
    view.setHeatRange(heatKind === 'marker' ? 1 : FIXED_HEAT_RANGE[heatKind]);
    view.showDistortion(heat);
  }
  view.setHeatMapVisible(Boolean(heat));

  const camera = new PerspectiveCamera(30, picture.width / picture.height, 0.001, 1000);
  const { lo, hi } = picture.frame;
  const center = new Vector3().fromArray(lo).add(new Vector3().fromArray(hi)).multiplyScalar(0.5);
  // The camera's axes: it looks along -direction, `up` made orthogonal.
  const back = new Vector3(...picture.direction).normalize();
  const right = new Vector3(...picture.up).cross(back).normalize();
  const up = back.clone().cross(right);
  // The nearest distance at which every corner of the box is in view, with a
  // margin of 4 % of the picture.
  const tanY = 0.96 * Math.tan((camera.fov * Math.PI) / 360);
  const tanX = tanY * camera.aspect;
  let distance = 0;
  for (let corner = 0; corner < 8; corner++) {
    const p = new Vector3(corner & 1 ? hi[0] : lo[0], corner & 2 ? hi[1] : lo[1], corner & 4 ? hi[2] : lo[2]).sub(center);
    const depth = p.dot(back);
    distance = Math.max(distance, depth + Math.abs(p.dot(right)) / tanX, depth + Math.abs(p.dot(up)) / tanY);
  }
  camera.position.copy(center).addScaledVector(back, distance);
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
