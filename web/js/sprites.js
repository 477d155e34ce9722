/**
 * Ball sprites: each ball pre-rendered as N cels of one turn of rolling, composited the way
 * Han & Zhu (2004) did it with bitmaps (a mask ANDed with the background, the sprite ORed on
 * top), here with canvas alpha compositing:
 *
 *  - a cel is the ball's painted surface (colour, stripe, number disc) seen from above after
 *    rolling k/N of a turn towards the sprite's +x; it is cut out by a round mask
 *    (`destination-in`), so only the disc is drawn;
 *  - the shading (limb darkening, the light's highlight) is one more sprite drawn over the
 *    cel, so the light stays put while the surface turns;
 *  - a soft shadow sprite is drawn under it.
 *
 * At draw time the cel is rotated to the ball's direction of travel; the server streams
 * which cel to show, so a rolling ball turns and a stopped ball stops turning.
 *
 * The balls are designed for a view from above, as a player reads a real table: a stripe's
 * band runs along the direction of roll (around the roll axis), so whatever the cel, the
 * band crosses the ball from above and its white caps stay at the sides: a striped ball is
 * never a white disc that reads as a second cue ball. The number sits on the band four
 * times, a quarter turn apart, so one number disc always faces up (on a solid too).
 */

import { ballColor, isStripe, CUE } from './balls.js';

export const CELS = 16;
const NUMBER_ANGLE = 0.5; // angular radius of the number disc (rad)
const INK_SAMPLES = 4; // per side of a pixel on a number disc: the digits' edges smooth
export const STRIPE_HALF = 0.5; // |b . S| below this is the coloured band
const DOT_ANGLE = 0.13; // the cue ball's red dots
const TILT = 0.3; // the cue ball's dots lean off the axes so they show as it rolls

/** The roll axis (the sprite's v, body frame): the stripe's band goes around it. */
const S = [0, 1, 0];
/** Number discs: on the band, a quarter turn apart; decal x = S x pole, decal y = S. */
const NUMBER_POLES = [[0, 0, 1], [1, 0, 0], [0, 0, -1], [-1, 0, 0]].map((d) => ({
  pole: d, e1: [S[1] * d[2] - S[2] * d[1], S[2] * d[0] - S[0] * d[2], S[0] * d[1] - S[1] * d[0]],
}));
const P = [0, Math.sin(TILT), Math.cos(TILT)];
const E2 = [0, Math.cos(TILT), -Math.sin(TILT)];
const CUE_DOTS = [P, [-P[0], -P[1], -P[2]], [1, 0, 0], [-1, 0, 0], E2, [-E2[0], -E2[1], -E2[2]]];

/** @typedef {number[]} Vec3 */
/** @typedef {HTMLCanvasElement | OffscreenCanvas} AnyCanvas */

/**
 * Every ball's pre-rendered images at one size (see buildSprites).
 * @typedef {object} Sprites
 * @property {number} radius ball radius, device pixels
 * @property {number} side side of a cel's square
 * @property {string} style the table style the balls are painted for
 * @property {Record<number, AnyCanvas[]>} cels id -> the CELS cels of one turn
 * @property {AnyCanvas} shade
 * @property {AnyCanvas} shadow
 */

/** @type {(a: Vec3, b: Vec3) => number} */
const dot3 = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];

/**
 * @param {string} hex '#rrggbb'
 * @returns {[number, number, number]}
 */
export function hexToRgb(hex) {
  const v = parseInt(hex.slice(1), 16);
  return [(v >> 16) & 255, (v >> 8) & 255, v & 255];
}

/**
 * The body point seen at sprite normal n = (u, v, w) after rolling `theta` radians towards
 * +u (rotation about the sprite's v axis).
 * @param {number} u
 * @param {number} v
 * @param {number} w
 * @param {number} theta
 * @returns {Vec3}
 */
export function bodyPoint(u, v, w, theta) {
  const c = Math.cos(theta);
  const s = Math.sin(theta);
  return [c * u - s * w, v, s * u + c * w];
}

/**
 * What paints body point b of ball `id`: returns {color: [r, g, b], decal: null | [x, y]}
 * where `decal` are number-disc coordinates in [-1, 1] when b is on a number disc. A
 * snooker ball (`style` "snooker") is its plain colour, as real ones are; the cue ball
 * keeps its dots on either table.
 * @param {number} id
 * @param {Vec3} b
 * @param {string} [style] the table's style
 * @returns {{color: number[], decal: [number, number] | null}}
 */
export function surfaceAt(id, b, style = 'pool') {
  if (id === CUE) {
    for (const d of CUE_DOTS) {
      if (dot3(b, d) > Math.cos(DOT_ANGLE)) return { color: [200, 30, 30], decal: null };
    }
    return { color: hexToRgb(ballColor(0)), decal: null };
  }
  if (style !== 'pool') return { color: hexToRgb(ballColor(id, style)), decal: null };
  const sinA = Math.sin(NUMBER_ANGLE);
  for (const { pole, e1 } of NUMBER_POLES) {
    if (dot3(b, pole) > Math.cos(NUMBER_ANGLE)) {
      return { color: [250, 248, 240], decal: [dot3(b, e1) / sinA, dot3(b, S) / sinA] };
    }
  }
  if (isStripe(id) && Math.abs(dot3(b, S)) > STRIPE_HALF) {
    return { color: [250, 248, 240], decal: null };
  }
  return { color: hexToRgb(ballColor(id)), decal: null };
}

/**
 * The 2D context of a canvas; every browser the game supports has one, so its absence is
 * an error rather than a case to draw around.
 * @param {HTMLCanvasElement | OffscreenCanvas} canvas
 * @param {CanvasRenderingContext2DSettings} [options]
 * @returns {CanvasRenderingContext2D}
 */
export function context2d(canvas, options) {
  const ctx = canvas.getContext('2d', options);
  if (!ctx) throw new Error('this browser cannot draw on a canvas');
  return /** @type {CanvasRenderingContext2D} */ (ctx);
}

/**
 * @param {number} w
 * @param {number} h
 * @returns {AnyCanvas}
 */
function makeCanvas(w, h) {
  if (typeof OffscreenCanvas !== 'undefined') return new OffscreenCanvas(w, h);
  const c = document.createElement('canvas');
  c.width = w;
  c.height = h;
  return c;
}

/**
 * Coverage maps (0..1) of each number 1..15 painted in a small square.
 * @param {number} size
 * @returns {Record<number, Float32Array>}
 */
function numberDecals(size) {
  /** @type {Record<number, Float32Array>} */
  const decals = {};
  const c = makeCanvas(size, size);
  const ctx = context2d(c, { willReadFrequently: true });
  for (let n = 1; n <= 15; n++) {
    ctx.clearRect(0, 0, size, size);
    ctx.fillStyle = '#000';
    ctx.textAlign = 'center';
    ctx.textBaseline = 'middle';
    const text = String(n);
    // As tall as the disc allows (a number read at 1x, ~5 px tall before); two digits
    // narrowed to fit side by side rather than set smaller.
    ctx.font = `bold ${Math.round(size * 0.86)}px system-ui, "DejaVu Sans", Arial, sans-serif`;
    ctx.save();
    ctx.translate(size / 2, size / 2 + size * 0.05);
    if (text.length > 1) ctx.scale(0.72, 1);
    ctx.fillText(text, 0, 0);
    ctx.restore();
    const data = ctx.getImageData(0, 0, size, size).data;
    const cov = new Float32Array(size * size);
    for (let i = 0; i < size * size; i++) cov[i] = data[i * 4 + 3] / 255;
    decals[n] = cov;
  }
  return decals;
}

/**
 * @param {Float32Array} cov
 * @param {number} size
 * @param {number} x
 * @param {number} y
 */
function sampleDecal(cov, size, x, y) {
  const px = Math.floor(((x + 1) / 2) * size);
  const py = Math.floor(((y + 1) / 2) * size);
  if (px < 0 || py < 0 || px >= size || py >= size) return 0;
  return cov[py * size + px];
}

/**
 * The share of pixel (px, py) of a cel that a number's ink covers, sampled on a grid
 * within the pixel: one sample a pixel drew the digits jagged and hard to tell apart on a
 * small ball (12, 13 and 15 at 1x).
 * @param {number} id
 * @param {Float32Array} cov the number's coverage map
 * @param {number} size its side
 * @param {number} px
 * @param {number} py
 * @param {number} side the cel's side
 * @param {number} r the ball's radius (pixels)
 * @param {number} theta the cel's turn
 */
function inkAt(id, cov, size, px, py, side, r, theta) {
  let ink = 0;
  for (let i = 0; i < INK_SAMPLES; i++) {
    for (let j = 0; j < INK_SAMPLES; j++) {
      const u = (px + (i + 0.5) / INK_SAMPLES - side / 2) / r;
      const v = (py + (j + 0.5) / INK_SAMPLES - side / 2) / r;
      const q = u * u + v * v;
      if (q >= 1) continue;
      const { decal } = surfaceAt(id, bodyPoint(u, v, Math.sqrt(1 - q), theta));
      if (decal) ink += sampleDecal(cov, size, decal[0], decal[1]);
    }
  }
  return ink / (INK_SAMPLES * INK_SAMPLES);
}

/**
 * A round mask of radius r (device pixels) in a square of side `side`.
 * @param {number} side
 * @param {number} r
 */
function roundMask(side, r) {
  const m = makeCanvas(side, side);
  const ctx = context2d(m);
  ctx.fillStyle = '#fff';
  ctx.beginPath();
  ctx.arc(side / 2, side / 2, r, 0, Math.PI * 2);
  ctx.fill();
  return m;
}

/**
 * The N cels of one ball: canvases of side `side` with the ball of radius r centred.
 * @param {number} id
 * @param {number} side
 * @param {number} r
 * @param {Record<number, Float32Array>} decals
 * @param {number} decalSize
 * @param {AnyCanvas} mask
 */
function ballCels(id, side, r, decals, decalSize, mask, style = 'pool') {
  /** @type {AnyCanvas[]} */
  const cels = [];
  for (let k = 0; k < CELS; k++) {
    const theta = (2 * Math.PI * k) / CELS;
    const surface = makeCanvas(side, side);
    const ctx = context2d(surface);
    const img = ctx.createImageData(side, side);
    const data = img.data;
    for (let py = 0; py < side; py++) {
      for (let px = 0; px < side; px++) {
        let u = (px + 0.5 - side / 2) / r;
        let v = (py + 0.5 - side / 2) / r;
        const q = u * u + v * v;
        if (q > 1.2) continue; // well outside the disc: the mask removes it anyway
        if (q > 1) { const n = Math.sqrt(q); u /= n; v /= n; }
        const w = Math.sqrt(Math.max(0, 1 - u * u - v * v));
        const b = bodyPoint(u, v, w, theta);
        const { color, decal } = surfaceAt(id, b, style);
        let [cr, cg, cb] = color;
        if (decal && decals[id]) {
          const ink = inkAt(id, decals[id], decalSize, px, py, side, r, theta);
          cr *= 1 - ink; cg *= 1 - ink; cb *= 1 - ink;
          cr += 20 * ink; cg += 20 * ink; cb += 20 * ink;
        }
        const i = (py * side + px) * 4;
        data[i] = cr; data[i + 1] = cg; data[i + 2] = cb; data[i + 3] = 255;
      }
    }
    ctx.putImageData(img, 0, 0);
    // The mask: keep the surface only where the disc is (Han & Zhu's AND).
    ctx.globalCompositeOperation = 'destination-in';
    ctx.drawImage(mask, 0, 0);
    ctx.globalCompositeOperation = 'source-over';
    cels.push(surface);
  }
  return cels;
}

/**
 * Light and shade over the disc, fixed in screen space (light from the top left).
 * @param {number} side
 * @param {number} r
 * @param {AnyCanvas} mask
 */
function shadeSprite(side, r, mask) {
  const c = makeCanvas(side, side);
  const ctx = context2d(c);
  const m = side / 2;
  const limb = ctx.createRadialGradient(m - r * 0.3, m - r * 0.35, r * 0.1, m, m, r * 1.02);
  limb.addColorStop(0, 'rgba(255,255,255,0.10)');
  limb.addColorStop(0.55, 'rgba(0,0,0,0)');
  limb.addColorStop(0.85, 'rgba(0,0,0,0.22)');
  limb.addColorStop(1, 'rgba(0,0,0,0.55)');
  ctx.fillStyle = limb;
  ctx.fillRect(0, 0, side, side);
  const spec = ctx.createRadialGradient(m - r * 0.38, m - r * 0.42, 0, m - r * 0.38,
    m - r * 0.42, r * 0.38);
  spec.addColorStop(0, 'rgba(255,255,255,0.95)');
  spec.addColorStop(0.35, 'rgba(255,255,255,0.45)');
  spec.addColorStop(1, 'rgba(255,255,255,0)');
  ctx.fillStyle = spec;
  ctx.fillRect(0, 0, side, side);
  const bounce = ctx.createRadialGradient(m + r * 0.45, m + r * 0.5, 0, m + r * 0.45,
    m + r * 0.5, r * 0.5);
  bounce.addColorStop(0, 'rgba(255,255,255,0.18)');
  bounce.addColorStop(1, 'rgba(255,255,255,0)');
  ctx.fillStyle = bounce;
  ctx.fillRect(0, 0, side, side);
  ctx.globalCompositeOperation = 'destination-in';
  ctx.drawImage(mask, 0, 0);
  return c;
}

/**
 * @param {number} side
 * @param {number} r
 */
function shadowSprite(side, r) {
  const c = makeCanvas(side, side);
  const ctx = context2d(c);
  const m = side / 2;
  const g = ctx.createRadialGradient(m, m, r * 0.2, m, m, r * 1.25);
  g.addColorStop(0, 'rgba(0,0,0,0.55)');
  g.addColorStop(0.7, 'rgba(0,0,0,0.25)');
  g.addColorStop(1, 'rgba(0,0,0,0)');
  ctx.fillStyle = g;
  ctx.fillRect(0, 0, side, side);
  return c;
}

/**
 * Build every ball's cels for a ball radius of `radiusPx` device pixels.
 * @param {number} radiusPx
 * @param {number[]} [ids]
 * @param {string} [style] the table's style ("pool", "snooker"): how the balls are painted
 * @returns {Sprites}
 */
export function buildSprites(radiusPx, ids = [...Array(16).keys()], style = 'pool') {
  const r = Math.max(4, radiusPx);
  const side = Math.ceil(2 * r + 4);
  const mask = roundMask(side, r);
  const decalSize = 48;
  const decals = numberDecals(decalSize);
  /** @type {Record<number, AnyCanvas[]>} */
  const cels = {};
  for (const id of ids) cels[id] = ballCels(id, side, r, decals, decalSize, mask, style);
  return { radius: r, side, style, cels, shade: shadeSprite(side, r, mask),
    shadow: shadowSprite(Math.ceil(side * 1.4), r) };
}

/**
 * Draw ball `id` centred at (x, y) device pixels: shadow, the rolled cel turned to the
 * travel direction `heading` (screen radians), then the fixed shading.
 * @param {CanvasRenderingContext2D} ctx
 * @param {Sprites} sprites
 * @param {number} id
 * @param {number} x
 * @param {number} y
 * @param {number} cel
 * @param {number} heading
 * @param {number} [scale]
 * @param {number} [lift] the ball's height above the bed, in radii (0 on it)
 */
export function drawBall(ctx, sprites, id, x, y, cel, heading, scale = 1, lift = 0) {
  const cels = sprites.cels[id];
  if (!cels) return;
  // A flying ball (lift: its height in radii) is nearer the eye, so drawn larger, and its
  // shadow falls further off, smaller and fainter.
  const up = Math.min(Math.max(lift, 0), 4);
  const side = sprites.side * scale * (1 + 0.12 * up);
  const sh = sprites.shadow.width * scale * (1 - 0.08 * up);
  const off = sprites.radius * 0.22 * scale * (1 + 2.5 * up);
  if (up > 0) {
    ctx.save();
    ctx.globalAlpha = 1 / (1 + 0.6 * up);
  }
  ctx.drawImage(sprites.shadow, x - sh / 2 + off, y - sh / 2 + off * 1.2, sh, sh);
  if (up > 0) ctx.restore();
  ctx.save();
  ctx.translate(x, y);
  ctx.rotate(heading);
  ctx.drawImage(cels[((cel % CELS) + CELS) % CELS], -side / 2, -side / 2, side, side);
  ctx.restore();
  ctx.drawImage(sprites.shade, x - side / 2, y - side / 2, side, side);
}
