// A .gltf whose buffers are data: URIs, packed into a GLB before GLTFLoader
// reads it. GLTFLoader loads a data: URI with fetch(), which a strict
// Content-Security-Policy refuses (the site's connect-src is 'self'): the
// form of .gltf the page asks for ("its buffers embedded") did not open. The
// GLB holds the same bytes: the buffers end to end (each 4-byte aligned) in
// its binary chunk, the buffer views moved by their buffer's offset.
import { GltfImportError } from './gltf-import-error.js';

const DATA_URI = /^data:[^,]*?(;base64)?,(.*)$/s;

/** The GLB of `json` when its buffers are data: URIs; null when it has none to pack. */
export function embeddedBuffersAsGlb(json, name) {
  const buffers = Array.isArray(json?.buffers) ? json.buffers : [];
  if (buffers.length === 0 || !buffers.every((buffer) => typeof buffer?.uri === 'string' && buffer.uri.startsWith('data:'))) {
    return null;
  }
  const parts = buffers.map((buffer, index) => decodeBuffer(buffer, index, name));
  const offsets = [];
  let total = 0;
  for (const part of parts) {
    offsets.push(total);
    total += align4(part.length);
  }
  const bin = new Uint8Array(total);
  parts.forEach((part, index) => bin.set(part, offsets[index]));

  const packed = structuredClone(json);
  packed.buffers = [{ byteLength: total }];
  const move = (view) => {
    if (!view || !Number.isInteger(view.buffer) || view.buffer < 0 || view.buffer >= parts.length) return;
    view.byteOffset = (view.byteOffset ?? 0) + offsets[view.buffer];
    view.buffer = 0;
  };
  for (const view of packed.bufferViews ?? []) {
    move(view);
    move(view?.extensions?.EXT_meshopt_compression);
  }
  return glb(packed, bin);
}

function decodeBuffer(buffer, index, name) {
  const match = DATA_URI.exec(buffer.uri);
  if (!match) throw new GltfImportError(`${name}: buffer ${index}'s data: URI has no ',' before its data.`);
  let bytes;
  try {
    const text = match[1] ? atob(match[2].replace(/\s+/g, '')) : decodePercent(match[2]);
    bytes = Uint8Array.from(text, (char) => char.charCodeAt(0));
  } catch {
    throw new GltfImportError(`${name}: buffer ${index}'s data: URI is not valid base64.`);
  }
  if (Number.isInteger(buffer.byteLength) && bytes.length < buffer.byteLength) {
    throw new GltfImportError(`${name}: buffer ${index} declares ${buffer.byteLength} bytes, its data: URI holds ${bytes.length}.`);
  }
  return bytes;
}

// %XX escapes as the bytes they name (a data: URI's bytes, not UTF-8 text).
function decodePercent(text) {
  return text.replace(/%([0-9a-fA-F]{2})/g, (_, hex) => String.fromCharCode(parseInt(hex, 16)));
}

const align4 = (n) => (n + 3) & ~3;

function glb(json, bin) {
  const jsonBytes = new TextEncoder().encode(JSON.stringify(json));
  const jsonLength = align4(jsonBytes.length);
  const total = 12 + 8 + jsonLength + 8 + bin.length;
  const out = new Uint8Array(total);
  const view = new DataView(out.buffer);
  view.setUint32(0, 0x46546c67, true); // 'glTF'
  view.setUint32(4, 2, true);
  view.setUint32(8, total, true);
  view.setUint32(12, jsonLength, true);
  view.setUint32(16, 0x4e4f534a, true); // 'JSON'
  out.set(jsonBytes, 20);
  out.fill(0x20, 20 + jsonBytes.length, 20 + jsonLength); // padded with spaces
  view.setUint32(20 + jsonLength, bin.length, true);
  view.setUint32(24 + jsonLength, 0x004e4942, true); // 'BIN'
  out.set(bin, 28 + jsonLength);
  return out.buffer;
}
