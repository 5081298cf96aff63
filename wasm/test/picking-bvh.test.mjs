// The picking BVH is built in the solver worker (web/src/worker/mesh-display.js)
// and attached on the page to its own copy of the mesh (Picker.attach): every
// pick must be the one a BVH built on the page gives, and the arrays the page
// draws must be the ones the tree was built on.
import assert from 'node:assert/strict';
import { before, test } from 'node:test';
// three and three-mesh-bvh as the web app resolves them (web/node_modules: the copies picker.js uses).
import { BufferAttribute, BufferGeometry, PerspectiveCamera, Vector3 } from '../../web/node_modules/three/build/three.module.js';
import { MeshBVH } from '../../web/node_modules/three-mesh-bvh/src/index.js';

import { Picker } from '../../web/src/interaction/picker.js';
import { Request } from '../../web/src/worker/protocol.js';
import { SessionHost } from '../../web/src/worker/session-host.js';
import { boundingBox, loadAnisoform, meshBytes } from '../node-support.mjs';

let wasm;
before(async () => {
  ({ wasm } = await loadAnisoform());
});

const WIDTH = 600;
const HEIGHT = 400;

function loaded(relative) {
  const host = new SessionHost(wasm, () => {});
  const bytes = meshBytes(relative);
  const reply = host.handle(Request.loadFile, { source: bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.length), name: relative.split('/').pop() });
  return { host, ...reply };
}

/** The geometry as MeshView.setMesh builds it: its own copies of the payload's arrays. */
function pageGeometry({ positions, triangles }) {
  const geometry = new BufferGeometry();
  geometry.setAttribute('position', new BufferAttribute(new Float32Array(positions), 3));
  geometry.setIndex(new BufferAttribute(new Uint32Array(triangles), 1));
  return geometry;
}

/** A Picker over `geometry` looking at the mesh from `direction` (a viewer stub: camera and toNdc). */
function pickerLookingFrom(geometry, direction) {
  const { min, max, diagonal } = boundingBox(geometry.getAttribute('position').array);
  const center = new Vector3().fromArray(min).add(new Vector3().fromArray(max)).multiplyScalar(0.5);
  const camera = new PerspectiveCamera(35, WIDTH / HEIGHT, diagonal / 100, diagonal * 100);
  camera.position.copy(center).addScaledVector(new Vector3(...direction).normalize(), 0.9 * diagonal);
  camera.lookAt(center);
  camera.updateMatrixWorld();
  const viewer = { camera, toNdc: (x, y) => ({ x: (x / WIDTH) * 2 - 1, y: -(y / HEIGHT) * 2 + 1 }) };
  return new Picker(viewer, { geometry });
}

test("the worker's BVH, attached to the page's copy of the armadillo, picks exactly what a BVH built on the page picks", () => {
  const { host, result, transfer } = loaded('closed/armadillo.off');
  try {
    // The tree travels as transferables: its roots and its triangle order, no copies.
    for (const root of result.bvh.roots) assert.ok(transfer.includes(root), 'each root is transferred');
    assert.ok(transfer.includes(result.bvh.indirectBuffer.buffer), 'the indirect buffer is transferred');
    assert.equal(result.bvh.index, undefined, 'the triangles travel once, as the payload\'s');
    // Indirect mode left the triangles as the core has them: the page draws those.
    assert.deepEqual(result.triangles, host.session.triangles());
    assert.deepEqual(result.positions, host.session.positions());

    const fromWorker = pageGeometry(result);
    const onPage = pageGeometry(result);
    const views = [[0.8, 0.35, -1], [-1, 0.2, 0.6], [0.1, -1, 0.3]];
    let rays = 0;
    let hits = 0;
    for (const direction of views) {
      const worker = pickerLookingFrom(fromWorker, direction);
      worker.attach(result.bvh);
      const page = pickerLookingFrom(onPage, direction);
      page.bvh = new MeshBVH(onPage, { indirect: true }); // built on the page, as three-mesh-bvh documents it
      for (let x = 15; x < WIDTH; x += 30) {
        for (let y = 20; y < HEIGHT; y += 40) {
          const expected = page.pick(x, y);
          assert.deepEqual(worker.pick(x, y), expected, `pixel (${x}, ${y}) seen from ${direction}`);
          rays++;
          if (expected) hits++;
        }
      }
      // The brush's query: the same vertices at the same distances.
      const hit = page.pick(WIDTH / 2, HEIGHT / 2);
      assert.ok(hit, 'the centre of the view is on the mesh');
      const { diagonal } = boundingBox(result.positions);
      const within = (picker) => {
        const visited = [];
        picker.forEachVertexInSphere(hit.point, 0.1 * diagonal, (vertex, distance) => visited.push([vertex, distance]));
        return visited.sort((a, b) => a[0] - b[0]);
      };
      const expected = within(page);
      assert.ok(expected.length > 10, `${expected.length} vertices in the brush`);
      assert.deepEqual(within(worker), expected);
    }
    assert.equal(rays, 600);
    assert.ok(hits > 150, `${hits} of ${rays} rays hit the armadillo`);
    // Attaching wrote nothing into the page's geometry.
    assert.deepEqual(fromWorker.index.array, result.triangles);
  } finally {
    host.session.delete();
  }
});

test("the worker's normals are the area-weighted vertex normals three computes", () => {
  const { host, result } = loaded('closed/armadillo.off');
  try {
    const geometry = pageGeometry(result);
    geometry.computeVertexNormals();
    const expected = geometry.getAttribute('normal').array;
    assert.equal(result.normals.length, expected.length);
    let largest = 0;
    for (let i = 0; i < expected.length; i++) largest = Math.max(largest, Math.abs(result.normals[i] - expected[i]));
    assert.ok(largest < 1e-5, `largest difference ${largest}`);
  } finally {
    host.session.delete();
  }
});

test("a restart's seed (setMesh, display false) gets no normals or BVH: the page shows that mesh already", () => {
  const { host, result } = loaded('closed/spot_triangulated.obj');
  try {
    const seeded = host.handle(Request.setMesh, { positions: result.exact, triangles: result.triangles, weld: false, display: false });
    assert.equal(seeded.result.normals, undefined);
    assert.equal(seeded.result.bvh, undefined);
    assert.equal(seeded.transfer.length, 3);
    const shown = host.handle(Request.setMesh, { positions: result.exact, triangles: result.triangles, weld: false });
    assert.equal(shown.result.normals.length, result.positions.length);
    assert.ok(shown.result.bvh.roots.length > 0);
  } finally {
    host.session.delete();
  }
});
