// A small PNG decoder for the tests' screenshots and renders: 8-bit greyscale, RGB,
// greyscale+alpha or RGBA, not interlaced (what Chromium and primdecomp write), with
// Node's zlib. Returns {width, height, rgb: Uint8Array of width*height*3}; alpha is
// dropped (the screenshots are opaque).
import { inflateSync } from 'node:zlib';

const SIGNATURE = Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]);

export function decodePng(buf) {
  if (!Buffer.isBuffer(buf)) buf = Buffer.from(buf);
  if (buf.length < 8 || !buf.subarray(0, 8).equals(SIGNATURE)) throw new Error('not a PNG');
  let pos = 8;
  let width = 0, height = 0, depth = 0, colour = 0, interlace = 0;
  const idat = [];
  while (pos + 8 <= buf.length) {
    const len = buf.readUInt32BE(pos);
    const type = buf.toString('latin1', pos + 4, pos + 8);
    const body = buf.subarray(pos + 8, pos + 8 + len);
    pos += 12 + len;
    if (type === 'IHDR') {
      width = body.readUInt32BE(0);
      height = body.readUInt32BE(4);
      depth = body[8];
      colour = body[9];
      interlace = body[12];
    } else if (type === 'IDAT') idat.push(body);
    else if (type === 'IEND') break;
  }
  const channels = { 0: 1, 2: 3, 4: 2, 6: 4 }[colour];
  if (depth !== 8 || !channels || interlace !== 0)
    throw new Error(`unsupported PNG: depth ${depth}, colour type ${colour}, interlace ${interlace}`);
  const raw = inflateSync(Buffer.concat(idat));
  const stride = width * channels;
  const px = new Uint8Array(height * stride);
  for (let y = 0; y < height; y++) {
    const f = raw[y * (stride + 1)];
    const src = raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1));
    const out = px.subarray(y * stride, (y + 1) * stride);
    const up = y > 0 ? px.subarray((y - 1) * stride, y * stride) : null;
    for (let i = 0; i < stride; i++) {
      const a = i >= channels ? out[i - channels] : 0;
      const b = up ? up[i] : 0;
      const c = up && i >= channels ? up[i - channels] : 0;
      let v = src[i];
      if (f === 1) v += a;
      else if (f === 2) v += b;
      else if (f === 3) v += (a + b) >> 1;
      else if (f === 4) {
        const p = a + b - c, pa = Math.abs(p - a), pb = Math.abs(p - b), pc = Math.abs(p - c);
        v += pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
      } else if (f !== 0) throw new Error(`bad PNG filter ${f}`);
      out[i] = v & 255;
    }
  }
  const rgb = new Uint8Array(width * height * 3);
  for (let k = 0; k < width * height; k++) {
    const s = k * channels;
    if (channels >= 3) {
      rgb[3 * k] = px[s]; rgb[3 * k + 1] = px[s + 1]; rgb[3 * k + 2] = px[s + 2];
    } else {
      rgb[3 * k] = rgb[3 * k + 1] = rgb[3 * k + 2] = px[s];
    }
  }
  return { width, height, rgb };
}

/** Hue in degrees, saturation and value (0..1) of an RGB triple (0..255). */
export function hsv(r, g, b) {
  const max = Math.max(r, g, b), min = Math.min(r, g, b), d = max - min;
  let h = 0;
  if (d > 0) {
    if (max === r) h = 60 * (((g - b) / d + 6) % 6);
    else if (max === g) h = 60 * ((b - r) / d + 2);
    else h = 60 * ((r - g) / d + 4);
  }
  return [h, max ? d / max : 0, max / 255];
}

export function hexRgb(hex) {
  return [1, 3, 5].map((i) => parseInt(hex.slice(i, i + 2), 16));
}

/** Pixels of `img` inside rectangle `r` ({x, y, w, h}) whose hue is within `tol`
 * degrees of `hex`'s, saturation at least `minSat` and value at least `minVal`. */
export function countHue(img, r, hex, tol = 12, minSat = 0.3, minVal = 0.15) {
  const [h0] = hsv(...hexRgb(hex));
  let n = 0;
  for (let y = Math.max(0, r.y); y < Math.min(img.height, r.y + r.h); y++) {
    for (let x = Math.max(0, r.x); x < Math.min(img.width, r.x + r.w); x++) {
      const k = 3 * (y * img.width + x);
      const [h, s, v] = hsv(img.rgb[k], img.rgb[k + 1], img.rgb[k + 2]);
      const dh = Math.abs(h - h0);
      if (s >= minSat && v >= minVal && Math.min(dh, 360 - dh) <= tol) n++;
    }
  }
  return n;
}

/** Pixels of `img` inside `r` that differ from `hex` by more than `tol` in a channel. */
export function countNot(img, r, hex, tol = 6) {
  const c = hexRgb(hex);
  let n = 0;
  for (let y = Math.max(0, r.y); y < Math.min(img.height, r.y + r.h); y++) {
    for (let x = Math.max(0, r.x); x < Math.min(img.width, r.x + r.w); x++) {
      const k = 3 * (y * img.width + x);
      if (Math.abs(img.rgb[k] - c[0]) > tol || Math.abs(img.rgb[k + 1] - c[1]) > tol || Math.abs(img.rgb[k + 2] - c[2]) > tol) n++;
    }
  }
  return n;
}

/** Pixels of `img` inside `r` exactly of colour `hex`. */
export function countExact(img, r, hex) {
  return r.w * r.h - countNot(img, r, hex, 0);
}
