// A big mesh's GPU buffers go up over a few frames before it is first drawn
// (web/src/viewer/staged-upload.js): every buffer is held by the helper mesh
// in exactly one frame, at most STEP_BYTES a frame (a larger buffer alone),
// the mesh is shown after the last, and the helper leaves the scene empty.
import assert from 'node:assert/strict';
import { test } from 'node:test';
// three as the web app resolves it (web/node_modules: the one copy staged-upload.js uses).
import { BufferAttribute, BufferGeometry, MeshBasicMaterial, Scene } from '../../web/node_modules/three/build/three.module.js';

import { EventEmitter } from '../../web/src/shared/event-emitter.js';
import { STEP_BYTES, StagedUpload, uploadSteps } from '../../web/src/viewer/staged-upload.js';

/** MeshView's geometry for `vertexCount` vertices and twice as many triangles. */
function viewGeometry(vertexCount) {
  const geometry = new BufferGeometry();
  geometry.setAttribute('position', new BufferAttribute(new Float32Array(3 * vertexCount), 3));
  geometry.setIndex(new BufferAttribute(new Uint32Array(6 * vertexCount), 1));
  geometry.setAttribute('selectionWeight', new BufferAttribute(new Float32Array(vertexCount), 1));
  geometry.setAttribute('distortion', new BufferAttribute(new Float32Array(vertexCount), 1));
  geometry.setAttribute('normal', new BufferAttribute(new Float32Array(3 * vertexCount), 3));
  return geometry;
}

class ViewerStub extends EventEmitter {
  scene = new Scene();
  renders = 0;
  requestRender() {
    this.renders++;
  }
  /** One animation frame, as Viewer draws it (then 'frame'). */
  drawFrame() {
    const drawn = this.scene.children.map((mesh) => ({
      buffers: [...Object.values(mesh.geometry.attributes), mesh.geometry.index].filter(Boolean),
      drawCount: mesh.geometry.drawRange.count,
      material: mesh.material,
    }));
    this.emit('frame', performance.now());
    return drawn;
  }
}

test('an 800k-vertex mesh goes up in three frames of at most STEP_BYTES (the 19 MB index alone), then is shown', () => {
  const geometry = viewGeometry(800_000);
  const steps = uploadSteps(geometry);
  assert.deepEqual(steps.map((step) => step.map(([name]) => name)), [['position', 'selectionWeight', 'distortion'], ['normal'], ['index']]);

  const viewer = new ViewerStub();
  const material = new MeshBasicMaterial();
  const upload = new StagedUpload(viewer, material);
  let shown = 0;
  upload.upload(geometry, () => shown++);
  const held = new Set();
  for (let frame = 0; frame < steps.length; frame++) {
    assert.equal(shown, 0, `not shown before frame ${frame} is drawn`);
    const [helper, ...others] = viewer.drawFrame();
    assert.equal(others.length, 0);
    assert.equal(helper.drawCount, 0, 'the helper draws nothing');
    assert.equal(helper.material, material, "the mesh's own material: its program is compiled once");
    const added = helper.buffers.filter((buffer) => !held.has(buffer));
    const bytes = added.reduce((sum, buffer) => sum + buffer.array.byteLength, 0);
    assert.ok(added.length === 1 || bytes <= STEP_BYTES, `frame ${frame}: ${bytes} bytes in ${added.length} buffers`);
    for (const buffer of added) held.add(buffer);
  }
  assert.equal(shown, 1, 'shown after the last step is drawn');
  assert.deepEqual(new Set([...Object.values(geometry.attributes), geometry.index]), held, 'every buffer went up');
  assert.equal(viewer.scene.children.length, 0, 'the helper left the scene');
  viewer.drawFrame();
  assert.equal(shown, 1, 'and stopped listening');
});

test('a mesh whose buffers fit in one step is shown at once; a newer mesh abandons an upload in progress', () => {
  const viewer = new ViewerStub();
  const upload = new StagedUpload(viewer, new MeshBasicMaterial());
  let small = 0;
  upload.upload(viewGeometry(200_000), () => small++);
  assert.equal(small, 1, 'the 200k koala (11 MB) is shown within the call');
  assert.equal(viewer.scene.children.length, 0);

  let first = 0;
  upload.upload(viewGeometry(800_000), () => first++);
  viewer.drawFrame();
  let second = 0;
  upload.upload(viewGeometry(800_000), () => second++);
  for (let frame = 0; frame < 5; frame++) viewer.drawFrame();
  assert.equal(first, 0, 'the abandoned mesh is never shown');
  assert.equal(second, 1);
  assert.equal(viewer.scene.children.length, 0);
});

test("abandoning the helper empties it before it is disposed: the mesh's GPU buffers stay", () => {
  const viewer = new ViewerStub();
  const upload = new StagedUpload(viewer, new MeshBasicMaterial());
  upload.upload(viewGeometry(800_000), () => {});
  const helper = viewer.scene.children[0];
  let disposedWith = null;
  helper.geometry.addEventListener('dispose', () => {
    disposedWith = { attributes: Object.keys(helper.geometry.attributes), index: helper.geometry.index };
  });
  viewer.drawFrame();
  upload.cancel();
  assert.deepEqual(disposedWith, { attributes: [], index: null });
});
