// The light drawing a CPU rasteriser shows while a big mesh moves
// (web/src/viewer/interaction-proxy.js): its vertices are the mesh's own, so
// every frame it draws lies on the shape the solver computed; it is used only
// while something moves, and the full mesh comes back with fresh normals.
import assert from 'node:assert/strict';
import { after, before, test } from 'node:test';
// three as the web app resolves it (web/node_modules: the one copy the proxy module uses too).
import { BufferAttribute, BufferGeometry, Mesh, MeshBasicMaterial, Scene } from '../../web/node_modules/three/build/three.module.js';

import { InteractionProxy, PROXY_TRIANGLES } from '../../web/src/viewer/interaction-proxy.js';
import { simplifiedMesh } from '../../web/src/worker/display-proxy.js';
import { loadAnisoform, sessionWith } from '../node-support.mjs';

let wasm;
before(async () => {
  ({ wasm } = await loadAnisoform());
});

/** A mesh as MeshView builds it, from a real mesh loaded by the core. */
function meshFrom(relative) {
  const session = sessionWith(wasm, relative);
  try {
    const geometry = new BufferGeometry();
    const positions = session.positions().slice();
    const vertexCount = positions.length / 3;
    geometry.setAttribute('position', new BufferAttribute(positions, 3));
    geometry.setAttribute('normal', new BufferAttribute(new Float32Array(positions.length), 3));
    geometry.setAttribute('selectionWeight', new BufferAttribute(new Float32Array(vertexCount), 1));
    geometry.setAttribute('distortion', new BufferAttribute(new Float32Array(vertexCount), 1));
    geometry.setIndex(new BufferAttribute(session.triangles().slice(), 1));
    return geometry;
  } finally {
    session.delete();
  }
}

function viewerStub() {
  const renders = { count: 0 };
  return { scene: new Scene(), canvas: { dataset: {} }, requestRender: () => renders.count++, renders };
}

const proxies = [];
after(() => proxies.forEach((proxy) => proxy.dispose()));

async function shown(relative) {
  const viewer = viewerStub();
  const geometry = meshFrom(relative);
  const material = new MeshBasicMaterial();
  const mesh = new Mesh(geometry, material);
  const wireframe = new Mesh(geometry, material);
  viewer.scene.add(mesh, wireframe);
  const fullDrawn = { count: 0 };
  // The worker's simplification (SessionHost.simplify), of the mesh as loaded.
  const simplify = (triangles) => simplifiedMesh(geometry.getAttribute('position').array.slice(), geometry.index.array, triangles);
  const proxy = new InteractionProxy(viewer, material, { enabled: true, simplify, beforeFull: () => fullDrawn.count++ });
  proxies.push(proxy);
  await proxy.setMesh(geometry, mesh, wireframe);
  return { viewer, geometry, mesh, wireframe, proxy, fullDrawn };
}

function surfaceArea(positions, triangles) {
  let sum = 0;
  for (let t = 0; t < triangles.length; t += 3) {
    const [a, b, c] = [0, 1, 2].map((k) => 3 * triangles[t + k]);
    const u = [0, 1, 2].map((k) => positions[b + k] - positions[a + k]);
    const w = [0, 1, 2].map((k) => positions[c + k] - positions[a + k]);
    sum += Math.hypot(u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]) / 2;
  }
  return sum;
}

const proxyMesh = (viewer, full) => viewer.scene.children.find((object) => object.isMesh && object.geometry !== full.geometry);

test('while the armadillo moves, a simplified mesh over its own vertices is drawn, and the full mesh after', async () => {
  const { viewer, geometry, mesh, wireframe, proxy, fullDrawn } = await shown('closed/armadillo.off');
  assert.equal(proxy.drawing, false);
  assert.equal(viewer.canvas.dataset.detail, 'full');
  const light = proxyMesh(viewer, mesh);
  assert.ok(light, 'the proxy is in the scene');
  assert.equal(light.visible, false, 'and hidden until something moves');
  // Ready to draw as it is (an orbit moves no vertex): unit normals already.
  const built = light.geometry.getAttribute('normal').array;
  for (let p = 0; p < built.length / 3; p++) {
    assert.ok(Math.abs(Math.hypot(built[3 * p], built[3 * p + 1], built[3 * p + 2]) - 1) < 1e-5, `normal ${p} before any move`);
  }

  // A deformed shape arrives: the proxy's vertices are exactly the mesh's.
  const full = geometry.getAttribute('position').array;
  const moved = full.map((x, i) => x + 0.01 * Math.sin(i));
  proxy.moved();
  proxy.showPositions(moved);
  assert.equal(proxy.drawing, true);
  assert.equal(viewer.canvas.dataset.detail, 'proxy');
  assert.equal(mesh.visible, false);
  assert.equal(wireframe.visible, false, "the full mesh's wireframe would be wrong over the proxy");
  assert.equal(light.visible, true);
  const triangles = light.geometry.index.count / 3;
  assert.ok(triangles <= PROXY_TRIANGLES && triangles >= 0.8 * PROXY_TRIANGLES, `${triangles} triangles`);
  assert.equal(proxy.drawnTriangles, triangles);
  const lightPositions = light.geometry.getAttribute('position').array;
  const vertexCount = lightPositions.length / 3;
  assert.ok(vertexCount < geometry.getAttribute('position').count / 4, `${vertexCount} proxy vertices`);
  // Each proxy vertex is one of the mesh's, at its new position: match them by position.
  const byPosition = new Map();
  for (let v = 0; v < moved.length / 3; v++) byPosition.set(`${moved[3 * v]},${moved[3 * v + 1]},${moved[3 * v + 2]}`, v);
  for (let p = 0; p < vertexCount; p++) {
    const key = `${lightPositions[3 * p]},${lightPositions[3 * p + 1]},${lightPositions[3 * p + 2]}`;
    assert.ok(byPosition.has(key), `proxy vertex ${p} is a vertex of the mesh's new shape`);
  }
  // And it is the same surface, coarser: its area is the mesh's within 5 %
  // (a proxy whose triangles joined the wrong vertices would be far off).
  const area = surfaceArea(lightPositions, light.geometry.index.array);
  const fullArea = surfaceArea(moved, geometry.index.array);
  assert.ok(Math.abs(area / fullArea - 1) < 0.05, `proxy area ${area} vs ${fullArea}`);
  // Its normals are unit and follow its own triangles.
  const normals = light.geometry.getAttribute('normal').array;
  for (let p = 0; p < vertexCount; p++) {
    assert.ok(Math.abs(Math.hypot(normals[3 * p], normals[3 * p + 1], normals[3 * p + 2]) - 1) < 1e-5, `normal ${p}`);
  }

  // The selection and heat map follow too.
  const weights = new Float32Array(geometry.getAttribute('position').count).map((_, v) => (v % 7) / 7);
  proxy.showAttribute('selectionWeight', weights);
  const lightWeights = light.geometry.getAttribute('selectionWeight').array;
  for (let p = 0; p < vertexCount; p++) {
    const v = byPosition.get(`${lightPositions[3 * p]},${lightPositions[3 * p + 1]},${lightPositions[3 * p + 2]}`);
    assert.equal(lightWeights[p], weights[v]);
  }

  // Motion ends: the full mesh is drawn again, its normals refreshed first.
  const before = fullDrawn.count;
  proxy.settle();
  assert.equal(proxy.drawing, false);
  assert.equal(viewer.canvas.dataset.detail, 'full');
  assert.equal(mesh.visible, true);
  assert.equal(wireframe.visible, true);
  assert.equal(light.visible, false);
  assert.ok(fullDrawn.count > before, 'beforeFull ran before the full mesh was shown');
});

test('the proxy settles by itself once nothing has moved for a moment', async () => {
  const { viewer, proxy } = await shown('closed/armadillo.off');
  proxy.moved();
  assert.equal(viewer.canvas.dataset.detail, 'proxy');
  await new Promise((resolve) => setTimeout(resolve, 900));
  assert.equal(viewer.canvas.dataset.detail, 'full');
});

test('a small mesh, or a GPU, draws the full mesh throughout', async () => {
  const small = await shown('closed/spot_triangulated.obj');
  small.proxy.moved();
  assert.equal(small.proxy.drawing, false);
  assert.equal(small.mesh.visible, true);
  assert.equal(proxyMesh(small.viewer, small.mesh), undefined);

  const viewer = viewerStub();
  const geometry = meshFrom('closed/armadillo.off');
  const mesh = new Mesh(geometry);
  const gpu = new InteractionProxy(viewer, mesh.material, { enabled: false, simplify: () => assert.fail('a GPU needs no proxy') });
  proxies.push(gpu);
  await gpu.setMesh(geometry, mesh, new Mesh(geometry));
  gpu.moved();
  assert.equal(gpu.drawing, false);
  assert.equal(viewer.canvas.dataset.detail, 'full');
});
