// A pointer drag seen in 3D (METHOD §4.2): both pointer positions are
// unprojected onto the plane through the picked anchor point, parallel to the
// image plane. The difference is the drag as a world vector at that depth;
// its length sets the amount of a drag edit. The solver does the same
// unprojection itself from the camera matrices (direction type 'screen').
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
