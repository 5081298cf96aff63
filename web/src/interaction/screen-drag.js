// A pointer drag seen in 3D (METHOD §4.2): both pointer positions are
// unprojected onto the plane through the picked anchor point, parallel to the
// image plane. The difference is the drag as a world vector at that depth;
// its length sets the amount of a drag edit. The solver does the same
// unprojection itself from the camera matrices (direction type 'screen');
// given the picked normal it, and tangentDragVector here for the arrows,
// take the drag into the surface's tangent plane along the view rays.
import { Vector3 } from 'three';

const anchorNdc = new Vector3();
const fromWorld = new Vector3();
const toWorld = new Vector3();

/** World-space drag vector [x, y, z] at the anchor's depth. */
export function worldDragVector(viewer, from, to, anchor) {
  const camera = viewer.camera;
  camera.updateMatrixWorld();
  anchorNdc.fromArray(anchor).project(camera);
  const a = viewer.toNdc(from[0], from[1]);
  const b = viewer.toNdc(to[0], to[1]);
  fromWorld.set(a.x, a.y, anchorNdc.z).unproject(camera);
  toWorld.set(b.x, b.y, anchorNdc.z).unproject(camera);
  return toWorld.sub(fromWorld).toArray();
}

// The core's rule for a drag on a surface (screen_direction.h, kEdgeOnTangentPlane):
// a tangent plane whose shortest on-screen stretch is below this fraction of
// its longest is seen (nearly) edge-on and has no usable image.
const EDGE_ON_TANGENT_PLANE = 0.05;

/**
 * The tangent vector at `anchor` (plane through it with `normal`) whose
 * on-screen image runs along the drag, as the core's screen_drag_to_world
 * computes it for a 'screen' direction with camera.normal: the view ray
 * through the displaced pointer met with the tangent plane, to first order.
 * Projecting the image-plane drag along the normal instead turns a 45° drag
 * on a plane seen at an angle into a line seen at 60°. Null when the plane
 * is seen (nearly) edge-on.
 * @param {{view: ArrayLike<number>, projection: ArrayLike<number>, viewport: ArrayLike<number>}} camera
 *   column-major matrices (three.js elements) and [x, y, width, height] in CSS pixels, as viewer.cameraState()
 * @param {number[]} from pointer pixels (y down)
 * @param {number[]} to
 * @param {number[]} anchor the picked world point
 * @param {number[]} normal the surface normal there (any length)
 * @returns {number[] | null}
 */
export function tangentDragVector(camera, from, to, anchor, normal) {
  const { view, projection, viewport } = camera;
  // world -> clip, row r column c at [r][c].
  const m = [0, 1, 2, 3].map((r) => [0, 1, 2, 3].map((c) => {
    let sum = 0;
    for (let k = 0; k < 4; k++) sum += projection[4 * k + r] * view[4 * c + k];
    return sum;
  }));
  const clip = m.map((row) => row[0] * anchor[0] + row[1] * anchor[1] + row[2] * anchor[2] + row[3]);
  const w = clip[3];
  // Pixels per world unit (2 by 3): the derivative of the perspective division.
  const pixelRow = (r, scale) => [0, 1, 2].map((c) => (scale * (m[r][c] - (clip[r] / w) * m[3][c])) / w);
  const jacobian = [pixelRow(0, 0.5 * viewport[2]), pixelRow(1, -0.5 * viewport[3])];
  const n = normalized(normal);
  // Two orthonormal tangents (any pair: the result does not depend on them).
  const helper = Math.abs(n[0]) < 0.6 ? [1, 0, 0] : [0, 1, 0];
  const t1 = normalized(cross(helper, n));
  const t2 = cross(n, t1);
  const a = dot(jacobian[0], t1), b = dot(jacobian[0], t2);
  const c = dot(jacobian[1], t1), d = dot(jacobian[1], t2);
  // Singular values of [[a, b], [c, d]].
  const sum = Math.hypot(a + d, c - b), difference = Math.hypot(a - d, c + b);
  const largest = 0.5 * (sum + difference), smallest = 0.5 * Math.abs(sum - difference);
  if (!(smallest > EDGE_ON_TANGENT_PLANE * largest)) return null;
  const det = a * d - b * c;
  const dx = to[0] - from[0], dy = to[1] - from[1];
  const s = (d * dx - b * dy) / det, t = (a * dy - c * dx) / det;
  return [0, 1, 2].map((axis) => s * t1[axis] + t * t2[axis]);
}

/**
 * The unit direction a drag on the surface means at the picked hit: the
 * tangent vector seen along the drag (tangentDragVector); where the surface
 * is seen edge-on, the image-plane drag projected onto the tangent plane.
 */
export function surfaceDragDirection(viewer, from, to, hit) {
  const tangent = tangentDragVector(viewer.cameraState(), from, to, hit.point, hit.normal);
  if (tangent) return normalized(tangent);
  const drag = worldDragVector(viewer, from, to, hit.point);
  const n = normalized(hit.normal);
  const along = dot(drag, n);
  return normalized(drag.map((value, axis) => value - along * n[axis]));
}

function dot(a, b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

function cross(a, b) {
  return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
}

// Per document, the selected vertices' positions (all of them when none is
// selected), packed, with the positions and the selection version they came
// from: a drag asks for the extent along a new direction at every pointer
// move, over the same committed positions (an array replaced, never written:
// mesh-document.js) and selection.
const packedOf = new WeakMap();

function selectedPoints(document) {
  const { positions, selection, selectionCount, selectionVersion } = document;
  const packed = packedOf.get(document);
  if (packed?.positions === positions && packed.version === selectionVersion) return packed.points;
  const points = new positions.constructor(positions.length);
  let n = 0;
  for (let i = 0; i < positions.length / 3; i++) {
    if (selectionCount > 0 && selection[i] <= 0) continue;
    points[n++] = positions[3 * i];
    points[n++] = positions[3 * i + 1];
    points[n++] = positions[3 * i + 2];
  }
  packedOf.set(document, { positions, version: selectionVersion, points: points.subarray(0, n) });
  return points.subarray(0, n);
}

/** Extent (max - min) of the selected vertices (all if none) along a unit vector. */
export function extentAlong(document, unit) {
  const points = selectedPoints(document);
  let min = Infinity;
  let max = -Infinity;
  for (let i = 0; i < points.length; i += 3) {
    const value = points[i] * unit[0] + points[i + 1] * unit[1] + points[i + 2] * unit[2];
    if (value < min) min = value;
    if (value > max) max = value;
  }
  return max > min ? max - min : 0;
}

export function normalized(vector) {
  const length = Math.hypot(vector[0], vector[1], vector[2]);
  return length > 0 ? vector.map((value) => value / length) : [0, 0, 0];
}
