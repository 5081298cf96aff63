// Big meshes for the size-limit tests, made from the real 200k koala: every
// triangle split in four at its edge midpoints (800k vertices), read from and
// written to binary little-endian PLY (float x y z, uchar count + int indices).

/** {positions: Float64Array, triangles: Uint32Array} of the midpoint subdivision. */
export function subdivided(positions, triangles) {
  const out = Array.from(positions);
  const midpoints = new Map();
  const midpoint = (a, b) => {
    const key = a < b ? a * 2 ** 32 + b : b * 2 ** 32 + a;
    let m = midpoints.get(key);
    if (m === undefined) {
      m = out.length / 3;
      midpoints.set(key, m);
      for (let k = 0; k < 3; k++) out.push((positions[3 * a + k] + positions[3 * b + k]) / 2);
    }
    return m;
  };
  const faces = new Uint32Array(triangles.length * 4);
  for (let t = 0; t < triangles.length / 3; t++) {
    const [a, b, c] = triangles.subarray(3 * t, 3 * t + 3);
    const ab = midpoint(a, b);
    const bc = midpoint(b, c);
    const ca = midpoint(c, a);
    faces.set([a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca], 12 * t);
  }
  return { positions: new Float64Array(out), triangles: faces };
}

/** The mesh of a binary little-endian PLY with float x y z first and uchar/int triangle lists. */
export function readBinaryPly(bytes) {
  const headerEnd = bytes.indexOf('end_header\n') + 'end_header\n'.length;
  const header = bytes.subarray(0, headerEnd).toString();
  const vertices = Number(/element vertex (\d+)/.exec(header)[1]);
  const faces = Number(/element face (\d+)/.exec(header)[1]);
  const vertexProperties = header.split('element vertex')[1].split('element face')[0].match(/property/g).length;
  const view = new DataView(bytes.buffer, bytes.byteOffset + headerEnd);
  const positions = new Float64Array(3 * vertices);
  let offset = 0;
  for (let v = 0; v < vertices; v++, offset += 4 * vertexProperties) {
    for (let k = 0; k < 3; k++) positions[3 * v + k] = view.getFloat32(offset + 4 * k, true);
  }
  const triangles = new Uint32Array(3 * faces);
  for (let f = 0; f < faces; f++, offset += 13) {
    if (view.getUint8(offset) !== 3) throw new Error(`face ${f} is not a triangle`);
    for (let k = 0; k < 3; k++) triangles[3 * f + k] = view.getInt32(offset + 1 + 4 * k, true);
  }
  return { positions, triangles };
}

/** Binary little-endian PLY bytes of a triangle mesh. */
export function binaryPly({ positions, triangles }) {
  const vertices = positions.length / 3;
  const faces = triangles.length / 3;
  const header = Buffer.from(`ply\nformat binary_little_endian 1.0\nelement vertex ${vertices}\n`
    + 'property float x\nproperty float y\nproperty float z\n'
    + `element face ${faces}\nproperty list uchar int vertex_indices\nend_header\n`);
  const body = Buffer.alloc(12 * vertices + 13 * faces);
  let offset = 0;
  for (const value of positions) offset = body.writeFloatLE(value, offset);
  for (let f = 0; f < faces; f++) {
    offset = body.writeUInt8(3, offset);
    for (let k = 0; k < 3; k++) offset = body.writeInt32LE(triangles[3 * f + k], offset);
  }
  return Buffer.concat([header, body]);
}
