// A small, deterministic palette PNG writer for the gallery's pictures: the
// colours are reduced to at most 256 by median cut (no dithering, no
// randomness: the same pixels always give the same bytes) and deflated at
// level 9. About a third of the size of the browser's RGBA PNG, so the
// committed pictures stay small; no image tool needs installing.
import { deflateSync } from 'node:zlib';

/** rgba: width * height * 4 bytes, top row first; alpha is ignored. */
export function encodePalettePng(width, height, rgba) {
  const { palette, indexOf } = medianCut(rgba, 256);
  const rows = Buffer.alloc(height * (width + 1));
  for (let y = 0; y < height; y++) {
    rows[y * (width + 1)] = 0; // filter: none (the usual choice for palette images)
    for (let x = 0; x < width; x++) {
      const p = 4 * (y * width + x);
      rows[y * (width + 1) + 1 + x] = indexOf.get((rgba[p] << 16) | (rgba[p + 1] << 8) | rgba[p + 2]);
    }
  }
  const header = Buffer.alloc(13);
  header.writeUInt32BE(width, 0);
  header.writeUInt32BE(height, 4);
  header[8] = 8; // bit depth
  header[9] = 3; // colour type: palette
  return Buffer.concat([
    Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]),
    chunk('IHDR', header),
    chunk('PLTE', Buffer.from(palette.flat())),
    chunk('IDAT', deflateSync(rows, { level: 9 })),
    chunk('IEND', Buffer.alloc(0)),
  ]);
}

// Boxes of distinct colours, split at the pixel-weighted median of their
// longest side (the box with the most pixels times its extent first) until
// there are `size`; each colour maps to its box's pixel-weighted mean.
function medianCut(rgba, size) {
  const counts = new Map();
  for (let p = 0; p < rgba.length; p += 4) {
    const key = (rgba[p] << 16) | (rgba[p + 1] << 8) | rgba[p + 2];
    counts.set(key, (counts.get(key) ?? 0) + 1);
  }
  const channel = (key, k) => (key >> (16 - 8 * k)) & 255;
  const describe = (keys) => {
    let pixels = 0, longest = 0, extent = -1;
    for (const key of keys) pixels += counts.get(key);
    for (let k = 0; k < 3; k++) {
      let lo = 255, hi = 0;
      for (const key of keys) { lo = Math.min(lo, channel(key, k)); hi = Math.max(hi, channel(key, k)); }
      if (hi - lo > extent) { extent = hi - lo; longest = k; }
    }
    return { keys, pixels, longest, extent };
  };
  const boxes = [describe([...counts.keys()].sort((a, b) => a - b))];
  while (boxes.length < size) {
    let best = -1;
    for (let b = 0; b < boxes.length; b++) {
      if (boxes[b].keys.length < 2 || boxes[b].extent === 0) continue;
      if (best < 0 || boxes[b].pixels * boxes[b].extent > boxes[best].pixels * boxes[best].extent) best = b;
    }
    if (best < 0) break;
    const { keys, pixels, longest } = boxes[best];
    const sorted = [...keys].sort((a, b) => channel(a, longest) - channel(b, longest) || a - b);
    let seen = 0, cut = 1;
    for (; cut < sorted.length - 1; cut++) {
      seen += counts.get(sorted[cut - 1]);
      if (seen >= pixels / 2) break;
    }
    boxes.splice(best, 1, describe(sorted.slice(0, cut)), describe(sorted.slice(cut)));
  }
  const palette = [];
  const indexOf = new Map();
  boxes.forEach((box, index) => {
    const sum = [0, 0, 0];
    for (const key of box.keys) for (let k = 0; k < 3; k++) sum[k] += channel(key, k) * counts.get(key);
    palette.push(sum.map((s) => Math.round(s / box.pixels)));
    for (const key of box.keys) indexOf.set(key, index);
  });
  return { palette, indexOf };
}

const CRC_TABLE = Array.from({ length: 256 }, (_, n) => {
  let c = n;
  for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
  return c >>> 0;
});

function crc32(bytes) {
  let c = 0xffffffff;
  for (const byte of bytes) c = CRC_TABLE[(c ^ byte) & 255] ^ (c >>> 8);
  return (c ^ 0xffffffff) >>> 0;
}

function chunk(type, data) {
  const out = Buffer.alloc(12 + data.length);
  out.writeUInt32BE(data.length, 0);
  out.write(type, 4, 'ascii');
  data.copy(out, 8);
  out.writeUInt32BE(crc32(out.subarray(4, 8 + data.length)), 8 + data.length);
  return out;
}
