// SPDX-License-Identifier: MIT
// png.mjs: the few lines of PNG decoding the browser test needs to look at its screenshots (8-bit, not
// interlaced: what Chromium writes), with node's zlib - so the test needs no image package.

import zlib from 'node:zlib';

const SIGNATURE = Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]);
const CHANNELS = { 0: 1, 2: 3, 4: 2, 6: 4 };  // PNG colour type -> samples per pixel

/** Decodes a PNG into {width, height, channels, data} (rows of width * channels bytes, no filter bytes). */
export function decodePng(buffer) {
  if (!buffer.subarray(0, 8).equals(SIGNATURE)) throw new Error('not a PNG file');
  let offset = 8;
  let header = null;
  const idat = [];
  while (offset < buffer.length) {
    const length = buffer.readUInt32BE(offset);
    const type = buffer.toString('latin1', offset + 4, offset + 8);
    const body = buffer.subarray(offset + 8, offset + 8 + length);
    if (type === 'IHDR') {
      header = {
        width: body.readUInt32BE(0), height: body.readUInt32BE(4), depth: body[8], colourType: body[9],
        interlace: body[12],
      };
    } else if (type === 'IDAT') {
      idat.push(body);
    } else if (type === 'IEND') {
      break;
    }
    offset += 12 + length;
  }
  if (!header) throw new Error('PNG without IHDR');
  const channels = CHANNELS[header.colourType];
  if (header.depth !== 8 || !channels || header.interlace !== 0) {
    throw new Error(`unsupported PNG: depth ${header.depth}, colour type ${header.colourType}, interlace ${header.interlace}`);
  }
  const raw = zlib.inflateSync(Buffer.concat(idat));
  const { width, height } = header;
  const stride = width * channels;
  const data = new Uint8Array(stride * height);
  for (let y = 0; y < height; ++y) {
    const filter = raw[y * (stride + 1)];
    const src = raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1));
    const row = data.subarray(y * stride, (y + 1) * stride);
    const prev = y > 0 ? data.subarray((y - 1) * stride, y * stride) : null;
    for (let x = 0; x < stride; ++x) {
      const a = x >= channels ? row[x - channels] : 0;
      const b = prev ? prev[x] : 0;
      const c = prev && x >= channels ? prev[x - channels] : 0;
      let value = src[x];
      if (filter === 1) value += a;
      else if (filter === 2) value += b;
      else if (filter === 3) value += (a + b) >> 1;
      else if (filter === 4) {
        const p = a + b - c;
        const pa = Math.abs(p - a);
        const pb = Math.abs(p - b);
        const pc = Math.abs(p - c);
        value += pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
      } else if (filter !== 0) {
        throw new Error(`bad PNG filter ${filter} in row ${y}`);
      }
      row[x] = value & 255;
    }
  }
  return { width, height, channels, data };
}

/** RGB of pixel (x, y); grey images give grey triples. */
export function pixel(image, x, y) {
  const i = (y * image.width + x) * image.channels;
  const d = image.data;
  return image.channels >= 3 ? [d[i], d[i + 1], d[i + 2]] : [d[i], d[i], d[i]];
}

/**
 * Statistics over a rectangle {left, top, width, height} (page pixels; scaled by `scale` for HiDPI shots):
 * how many pixels pass each predicate in `tests` ({name: ([r, g, b]) => bool}), and the luminance spread.
 */
export function regionStats(image, rect, tests, scale = 1) {
  const x0 = Math.max(0, Math.floor(rect.left * scale));
  const y0 = Math.max(0, Math.floor(rect.top * scale));
  const x1 = Math.min(image.width, Math.ceil((rect.left + rect.width) * scale));
  const y1 = Math.min(image.height, Math.ceil((rect.top + rect.height) * scale));
  const counts = Object.fromEntries(Object.keys(tests).map((k) => [k, 0]));
  let n = 0;
  let sum = 0;
  let sum2 = 0;
  for (let y = y0; y < y1; ++y) {
    for (let x = x0; x < x1; ++x) {
      const rgb = pixel(image, x, y);
      const l = 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
      n += 1;
      sum += l;
      sum2 += l * l;
      for (const [k, test] of Object.entries(tests)) if (test(rgb)) counts[k] += 1;
    }
  }
  const mean = n ? sum / n : 0;
  return { pixels: n, counts, luminanceStd: n ? Math.sqrt(Math.max(0, sum2 / n - mean * mean)) : 0 };
}
