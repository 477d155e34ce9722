/**
 * Drawing on the table canvas. The table (wood, cushions, cloth, pockets, diamonds) is drawn
 * once per size into a cached layer; every frame draws that layer, then the balls (sprites),
 * the guide, the cue stick and the overlays. Sizes come from the server's table geometry, in
 * metres, through the view transform (geometry.js); the canvas backing store is in device
 * pixels (devicePixelRatio) so lines and sprites stay sharp.
 */

import { CUSHION_WIDTH, RAIL_WIDTH } from './geometry.js';
import { drawBall } from './sprites.js';
import { sinkPose } from './playback.js';

/** @typedef {import('./geometry.js').Table} Table */
/** @typedef {import('./geometry.js').View} View */
/** @typedef {import('./geometry.js').Vec} Vec */
/** @typedef {import('./sprites.js').Sprites} Sprites */
/** @typedef {CanvasRenderingContext2D} Ctx */

/**
 * @param {Ctx} ctx
 * @param {number} x
 * @param {number} y
 * @param {number} w
 * @param {number} h
 * @param {number} r corner radius
 */
function roundRect(ctx, x, y, w, h, r) {
  ctx.beginPath();
  ctx.moveTo(x + r, y);
  ctx.arcTo(x + w, y, x + w, y + h, r);
  ctx.arcTo(x + w, y + h, x, y + h, r);
  ctx.arcTo(x, y + h, x, y, r);
  ctx.arcTo(x, y, x + w, y, r);
  ctx.closePath();
}

/**
 * Unit direction from the middle of a pocket's mouth towards its hole.
 * @param {Table['pockets'][number]} p
 * @returns {Vec}
 */
export function pocketOutward(p) {
  if (p.outward) return p.outward;
  if (!p.jaws) return [0, 0];
  const mx = (p.jaws[0][0] + p.jaws[1][0]) / 2;
  const my = (p.jaws[0][1] + p.jaws[1][1]) / 2;
  const n = Math.hypot(p.center[0] - mx, p.center[1] - my) || 1;
  return [(p.center[0] - mx) / n, (p.center[1] - my) / n];
}

/**
 * @param {Ctx} ctx
 * @param {Vec[]} pts
 */
function polygon(ctx, pts) {
  ctx.beginPath();
  pts.forEach(([x, y], i) => (i ? ctx.lineTo(x, y) : ctx.moveTo(x, y)));
  ctx.closePath();
}

/**
 * The back corners of each cushion (where it meets the wooden rail): from each jaw along
 * the direction of that jaw's pocket until the rail line, so the cushion ends are cut like
 * real pocket facings. Returns [[backOfStart, backOfEnd], ...] in table metres.
 * @param {Table} table
 * @returns {Vec[][]}
 */
export function cushionBacks(table) {
  /** @type {(p: Vec, q: Vec) => boolean} */
  const near = (p, q) => Math.hypot(p[0] - q[0], p[1] - q[1]) < 1e-9;
  /** @param {Vec} j */
  const pocketAtJaw = (j) => table.pockets.find((p) => p.jaws && p.jaws.some((q) => near(q, j)));
  /** @param {{start: Vec, end: Vec}} c @param {Vec} j */
  const meeting = (c, j) => table.cushions.find((o) => o !== c
    && (near(o.start, j) || near(o.end, j)));
  return table.cushions.map((c) => {
    const [nx, ny] = c.normal;
    return [c.start, c.end].map((j) => {
      const other = meeting(c, j);
      if (other) { // a closed corner (carom): mitred to the rail's corner
        const [mx, my] = other.normal;
        return [j[0] - CUSHION_WIDTH * (nx + mx), j[1] - CUSHION_WIDTH * (ny + my)];
      }
      const pocket = pocketAtJaw(j);
      let [dx, dy] = pocket ? pocketOutward(pocket) : [-nx, -ny];
      const along = -(dx * nx + dy * ny); // how fast the cut goes back into the rail
      if (along < 0.2) { dx = -nx; dy = -ny; }
      const t = CUSHION_WIDTH / Math.max(0.2, -(dx * nx + dy * ny));
      return [j[0] + dx * t, j[1] + dy * t];
    });
  });
}

/**
 * @typedef {object} BedBox the bed's box on screen (CSS px) and the cushion and rail widths
 * @property {number} bx
 * @property {number} by
 * @property {number} bw
 * @property {number} bh
 * @property {number} cw
 * @property {number} rw
 */

/**
 * Draw the static table into `ctx` (already scaled to CSS pixels).
 * @param {Ctx} ctx
 * @param {Table} table
 * @param {View} view
 */
export function drawTable(ctx, table, view) {
  const s = view.scale;
  // The bed's box on screen (either orientation).
  const [c0x, c0y] = view.toScreen(0, 0);
  const [c1x, c1y] = view.toScreen(table.length, table.width);
  const box = { bx: Math.min(c0x, c1x), by: Math.min(c0y, c1y), bw: Math.abs(c1x - c0x),
    bh: Math.abs(c1y - c0y), cw: CUSHION_WIDTH * s, rw: RAIL_WIDTH * s };

  ctx.fillStyle = '#10161c';
  ctx.fillRect(0, 0, view.width, view.height);
  drawRails(ctx, view, box);
  drawPockets(ctx, table, view);
  drawBed(ctx, table, view, box);
  drawDiamonds(ctx, table, view);
  drawChalk(ctx, table, view);
}

/**
 * @param {Ctx} ctx
 * @param {View} view
 * @param {BedBox} box
 */
function drawRails(ctx, view, { bx, by, bw, bh, cw, rw }) {
  const s = view.scale;
  // Wooden rails.
  const ox = bx - cw - rw;
  const oy = by - cw - rw;
  const ow = bw + 2 * (cw + rw);
  const oh = bh + 2 * (cw + rw);
  const wood = ctx.createLinearGradient(ox, oy, ox + ow * 0.2, oy + oh);
  wood.addColorStop(0, '#6b3a1f');
  wood.addColorStop(0.5, '#542c16');
  wood.addColorStop(1, '#3f200f');
  ctx.fillStyle = wood;
  roundRect(ctx, ox, oy, ow, oh, rw * 0.6);
  ctx.fill();
  ctx.strokeStyle = 'rgba(255,220,180,0.25)';
  ctx.lineWidth = Math.max(1, s * 0.006);
  roundRect(ctx, ox + rw * 0.12, oy + rw * 0.12, ow - rw * 0.24, oh - rw * 0.24, rw * 0.5);
  ctx.stroke();
}

/**
 * @param {Ctx} ctx
 * @param {Table} table
 * @param {View} view
 */
function drawPockets(ctx, table, view) {
  const s = view.scale;
  // Pocket plates on the rails (dark leather around each hole).
  for (const p of table.pockets) {
    const [px, py] = view.toScreen(p.center[0], p.center[1]);
    ctx.fillStyle = '#1b1b1b';
    ctx.beginPath();
    ctx.arc(px, py, p.radius * s * 1.45, 0, Math.PI * 2);
    ctx.fill();
  }

  // Pocket throats and holes: from the mouth (between the jaws) back into the rail.
  table.pockets.forEach((p) => {
    if (!p.jaws) return;
    const [[ax, ay], [bx2, by2]] = p.jaws;
    const [ox2, oy2] = pocketOutward(p);
    const depth = CUSHION_WIDTH / Math.max(Math.abs(ox2), Math.abs(oy2));
    const throat = [[ax, ay], [bx2, by2], [bx2 + ox2 * depth, by2 + oy2 * depth],
      [ax + ox2 * depth, ay + oy2 * depth]].map(([x, y]) => view.toScreen(x, y));
    ctx.fillStyle = '#000';
    polygon(ctx, throat);
    ctx.fill();
    const [px, py] = view.toScreen(p.center[0], p.center[1]);
    const r = p.radius * s;
    const hole = ctx.createRadialGradient(px, py, r * 0.2, px, py, r);
    hole.addColorStop(0, '#000');
    hole.addColorStop(0.82, '#000');
    hole.addColorStop(1, '#262626');
    ctx.fillStyle = hole;
    ctx.beginPath();
    ctx.arc(px, py, r, 0, Math.PI * 2);
    ctx.fill();
  });
}

/**
 * @param {Ctx} ctx
 * @param {Table} table
 * @param {View} view
 * @param {BedBox} box
 */
function drawBed(ctx, table, view, { bx, by, bw, bh }) {
  const s = view.scale;
  const backs = cushionBacks(table);
  // Cloth on the bed, with a soft vignette from the lamp.
  const cloth = ctx.createRadialGradient(bx + bw / 2, by + bh / 2, Math.min(bw, bh) * 0.1,
    bx + bw / 2, by + bh / 2, Math.max(bw, bh) * 0.7);
  cloth.addColorStop(0, '#1f8a50');
  cloth.addColorStop(1, '#146339');
  ctx.fillStyle = cloth;
  // The bed runs from cushion nose to cushion nose and across each pocket's mouth line.
  polygon(ctx, table.cushions.flatMap((c) => [c.start, c.end]).map(([x, y]) => view.toScreen(x, y)));
  ctx.fill();

  // Cushions: cloth-covered rubber from each nose back to the rail, the ends cut along the
  // pocket's direction so the jaws open into the throat.
  table.cushions.forEach((c, i) => {
    const [b0, b1] = backs[i];
    const pts = [c.start, c.end, b1, b0].map(([x, y]) => view.toScreen(x, y));
    ctx.fillStyle = '#125a34';
    polygon(ctx, pts);
    ctx.fill();
    ctx.strokeStyle = 'rgba(190,255,210,0.3)';
    ctx.lineWidth = Math.max(1, s * 0.004);
    ctx.beginPath();
    ctx.moveTo(pts[0][0], pts[0][1]);
    ctx.lineTo(pts[1][0], pts[1][1]);
    ctx.stroke();
    ctx.strokeStyle = 'rgba(0,0,0,0.35)';
    ctx.beginPath();
    ctx.moveTo(pts[3][0], pts[3][1]);
    ctx.lineTo(pts[2][0], pts[2][1]);
    ctx.stroke();
  });
}

/**
 * @param {Ctx} ctx
 * @param {Table} table
 * @param {View} view
 */
function drawDiamonds(ctx, table, view) {
  const s = view.scale;
  const L = table.length;
  const W = table.width;
  // Diamonds (sights) on the rails: every eighth of the length, every quarter of the width.
  const mid = CUSHION_WIDTH + RAIL_WIDTH * 0.5;
  const dsz = Math.max(2, s * 0.012);
  /** @type {(x: number, y: number) => void} */
  const diamond = (x, y) => {
    const [dx, dy] = view.toScreen(x, y);
    ctx.beginPath();
    ctx.moveTo(dx, dy - dsz);
    ctx.lineTo(dx + dsz * 0.7, dy);
    ctx.lineTo(dx, dy + dsz);
    ctx.lineTo(dx - dsz * 0.7, dy);
    ctx.closePath();
    ctx.fill();
  };
  ctx.fillStyle = '#efe6cf';
  const carom = table.style === 'carom';
  for (let k = 1; k < 8; k++) {
    if (k === 4 && !carom) continue; // the side pocket's place
    diamond((L * k) / 8, -mid);
    diamond((L * k) / 8, W + mid);
  }
  for (let k = 1; k < 4; k++) {
    diamond(-mid, (W * k) / 4);
    diamond(L + mid, (W * k) / 4);
  }
  if (carom) drawDiamondNumbers(ctx, table, view);
}

/**
 * A carom table's aid to system aiming: each sight's number on the rail's outer edge, 0 to
 * 8 along the long rails from the head corner, 0 to 4 along the short rails from the bottom.
 * @param {Ctx} ctx
 * @param {Table} table
 * @param {View} view
 */
function drawDiamondNumbers(ctx, table, view) {
  const L = table.length;
  const W = table.width;
  const out = CUSHION_WIDTH + RAIL_WIDTH * 0.85;
  ctx.save();
  ctx.fillStyle = 'rgba(239,230,207,0.85)';
  ctx.font = `${Math.max(8, Math.round(view.scale * 0.03))}px system-ui, sans-serif`;
  ctx.textAlign = 'center';
  ctx.textBaseline = 'middle';
  /** @type {(x: number, y: number, n: number) => void} */
  const label = (x, y, n) => {
    const [sx, sy] = view.toScreen(x, y);
    ctx.fillText(String(n), sx, sy);
  };
  for (let k = 0; k <= 8; k++) {
    label((L * k) / 8, -out, k);
    label((L * k) / 8, W + out, k);
  }
  for (let k = 1; k < 4; k++) {
    label(-out, (W * k) / 4, k);
    label(L + out, (W * k) / 4, k);
  }
  ctx.restore();
}

/**
 * @param {Ctx} ctx
 * @param {Table} table
 * @param {View} view
 */
function drawChalk(ctx, table, view) {
  const s = view.scale;
  const L = table.length;
  const W = table.width;
  // Head string and spots, faint chalk marks.
  ctx.strokeStyle = 'rgba(255,255,255,0.12)';
  ctx.lineWidth = Math.max(1, s * 0.002);
  const [hx0, hy0] = view.toScreen(table.head_string, 0);
  const [hx1, hy1] = view.toScreen(table.head_string, W);
  ctx.beginPath();
  ctx.moveTo(hx0, hy0);
  ctx.lineTo(hx1, hy1);
  ctx.stroke();
  for (const arc of table.arcs ?? []) { // snooker's D
    const a0 = (arc.start_deg * Math.PI) / 180;
    const a1 = (arc.end_deg * Math.PI) / 180;
    // Sample the arc through the view (either orientation turns it).
    ctx.beginPath();
    for (let k = 0; k <= 48; k++) {
      const a = a0 + ((a1 - a0) * k) / 48;
      const [x, y] = view.toScreen(arc.center[0] + arc.radius * Math.cos(a),
        arc.center[1] + arc.radius * Math.sin(a));
      if (k === 0) ctx.moveTo(x, y); else ctx.lineTo(x, y);
    }
    ctx.stroke();
  }
  ctx.fillStyle = 'rgba(255,255,255,0.35)';
  const named = table.style && table.style !== 'pool' ? Object.values(table.spots ?? {}) : [];
  const spots = named.length ? named : [table.head_spot, table.foot_spot, [L / 2, W / 2]];
  for (const spot of spots) {
    if (!spot) continue;
    const [x, y] = view.toScreen(spot[0], spot[1]);
    ctx.beginPath();
    ctx.arc(x, y, Math.max(1.2, s * 0.004), 0, Math.PI * 2);
    ctx.fill();
  }
}

const BALL_RADIUS_M = 0.028575; // the WPA ball's radius: a flying ball's height in radii

/**
 * Balls at their (interpolated) positions: Map id -> {x, y, z, cel, heading}; a flying
 * ball (z > 0, metres) is drawn over the others, larger, with its shadow further off.
 * @param {Ctx} ctx
 * @param {View} view
 * @param {Sprites} sprites
 * @param {Map<number, {x: number, y: number, z?: number, cel?: number, heading?: number}>} balls
 * @param {number} scaleToCss
 */
export function drawBalls(ctx, view, sprites, balls, scaleToCss) {
  const height = (/** @type {number} */ id) => balls.get(id)?.z ?? 0;
  const ids = [...balls.keys()].sort((a, b) => height(a) - height(b) || a - b);
  for (const id of ids) {
    const b = balls.get(id);
    if (!b) continue;
    const [x, y] = view.toScreen(b.x, b.y);
    drawBall(ctx, sprites, id, x, y, b.cel ?? 0, view.screenAngle(b.heading ?? 0), scaleToCss,
      (b.z ?? 0) / BALL_RADIUS_M);
  }
}

/**
 * A ball being pocketed: slides into the hole, shrinking and darkening.
 * @param {Ctx} ctx
 * @param {View} view
 * @param {Sprites} sprites
 * @param {import('./playback.js').Sinking} sink
 * @param {number} now
 * @param {number} scaleToCss
 */
export function drawSinking(ctx, view, sprites, sink, now, scaleToCss) {
  const pose = sinkPose(sink, now);
  const [sx, sy] = view.toScreen(pose.x, pose.y);
  ctx.save();
  ctx.globalAlpha = pose.alpha;
  drawBall(ctx, sprites, sink.id, sx, sy, sink.cel, view.screenAngle(sink.heading),
    scaleToCss * pose.scale);
  ctx.restore();
}

/**
 * The curved part of a guide (a raised cue's swerve), in the guide line's dashes.
 * @param {Ctx} ctx
 * @param {View} view
 * @param {Table} table
 * @param {Vec[]} points table metres, in order
 */
export function drawPath(ctx, view, table, points) {
  const s = view.scale;
  const r = table.ball_radius * s;
  ctx.save();
  ctx.lineWidth = Math.max(1, s * 0.003);
  ctx.strokeStyle = 'rgba(255,255,255,0.75)';
  ctx.setLineDash([Math.max(3, r * 0.5), Math.max(3, r * 0.4)]);
  ctx.beginPath();
  points.forEach(([x, y], i) => {
    const [px, py] = view.toScreen(x, y);
    if (i === 0) ctx.moveTo(px, py); else ctx.lineTo(px, py);
  });
  ctx.stroke();
  ctx.restore();
}

/**
 * The guide line, the ghost ball and the object ball's likely path.
 * @param {Ctx} ctx
 * @param {View} view
 * @param {Table} table
 * @param {Vec} cue
 * @param {import('./geometry.js').Guide} guide
 * @param {Vec | null} [objectEnd] where the object ball's line ends (`objectPath`): at the
 *   rail, a ball or the pocket it drops in; without it a short stub is drawn
 */
export function drawGuide(ctx, view, table, cue, guide, objectEnd = null) {
  const s = view.scale;
  const r = table.ball_radius * s;
  const [cx, cy] = view.toScreen(cue[0], cue[1]);
  const [gx, gy] = view.toScreen(guide.contact[0], guide.contact[1]);
  ctx.save();
  ctx.lineWidth = Math.max(1, s * 0.003);
  ctx.strokeStyle = 'rgba(255,255,255,0.75)';
  ctx.setLineDash([Math.max(3, r * 0.5), Math.max(3, r * 0.4)]);
  ctx.beginPath();
  ctx.moveTo(cx, cy);
  ctx.lineTo(gx, gy);
  ctx.stroke();
  ctx.setLineDash([]);
  if (guide.kind !== 'none') {
    ctx.strokeStyle = 'rgba(255,255,255,0.85)';
    ctx.beginPath();
    ctx.arc(gx, gy, r, 0, Math.PI * 2);
    ctx.stroke();
  }
  /** @type {(dir: Vec | null, len: number, color: string) => void} */
  const ray = (dir, len, color) => {
    if (!dir) return;
    const [ex, ey] = view.toScreen(guide.contact[0] + dir[0] * len,
      guide.contact[1] + dir[1] * len);
    ctx.strokeStyle = color;
    ctx.beginPath();
    ctx.moveTo(gx, gy);
    ctx.lineTo(ex, ey);
    ctx.stroke();
  };
  if (guide.kind === 'ball' && guide.objectDir) {
    const [hx, hy] = [guide.contact[0] + guide.objectDir[0] * 2 * table.ball_radius,
      guide.contact[1] + guide.objectDir[1] * 2 * table.ball_radius];
    const [ox, oy] = view.toScreen(hx, hy);
    const [ex, ey] = objectEnd ? view.toScreen(objectEnd[0], objectEnd[1])
      : view.toScreen(hx + guide.objectDir[0] * 0.15, hy + guide.objectDir[1] * 0.15);
    ctx.lineWidth = Math.max(1.5, s * 0.004);
    ctx.strokeStyle = 'rgba(255,230,120,0.9)';
    ctx.beginPath();
    ctx.moveTo(ox, oy);
    ctx.lineTo(ex, ey);
    ctx.stroke();
    ctx.lineWidth = Math.max(1, s * 0.002);
    ray(guide.cueDir, 0.15, 'rgba(255,255,255,0.45)');
  } else if (guide.kind !== 'none') {
    ray(guide.cueDir, 0.2, 'rgba(255,255,255,0.45)');
  }
  ctx.restore();
}

/**
 * The cue stick behind the cue ball along `angle` (table radians), pulled back by `power`
 * (0..1). `alpha` < 1 for the opponent's relayed aim.
 * @param {Ctx} ctx
 * @param {View} view
 * @param {Table} table
 * @param {Vec} cue
 * @param {number} angle
 * @param {number} power
 * @param {number} [alpha]
 */
export function drawCue(ctx, view, table, cue, angle, power, alpha = 1) {
  const s = view.scale;
  const r = table.ball_radius;
  const gap = r * 1.25 + power * 0.22;
  const length = 1.45;
  const dx = Math.cos(angle);
  const dy = Math.sin(angle);
  const tip = [cue[0] - dx * gap, cue[1] - dy * gap];
  const butt = [tip[0] - dx * length, tip[1] - dy * length];
  const [tx, ty] = view.toScreen(tip[0], tip[1]);
  const [bx, by] = view.toScreen(butt[0], butt[1]);
  const nx = -(by - ty);
  const ny = bx - tx;
  const nl = Math.hypot(nx, ny) || 1;
  const w0 = 0.0065 * s;
  const w1 = 0.015 * s;
  /** @type {(w: number) => Vec} */
  const side = (w) => [(nx / nl) * w, (ny / nl) * w];
  const [a0x, a0y] = side(w0);
  const [a1x, a1y] = side(w1);
  ctx.save();
  ctx.globalAlpha = alpha;
  // Shadow.
  ctx.fillStyle = 'rgba(0,0,0,0.3)';
  const sh = 0.012 * s;
  ctx.beginPath();
  ctx.moveTo(tx + a0x + sh, ty + a0y + sh);
  ctx.lineTo(bx + a1x + sh, by + a1y + sh);
  ctx.lineTo(bx - a1x + sh, by - a1y + sh);
  ctx.lineTo(tx - a0x + sh, ty - a0y + sh);
  ctx.fill();
  const grad = ctx.createLinearGradient(tx, ty, bx, by);
  grad.addColorStop(0, '#3a6fd8'); // chalked tip
  grad.addColorStop(0.012, '#f4ead2'); // ferrule
  grad.addColorStop(0.03, '#e2c48f'); // maple shaft
  grad.addColorStop(0.6, '#c99a5b');
  grad.addColorStop(0.62, '#2b1508'); // joint and ebony butt
  grad.addColorStop(0.75, '#5a2a12');
  grad.addColorStop(0.77, '#d9c7a0');
  grad.addColorStop(0.79, '#3b1a0a');
  grad.addColorStop(1, '#1a0c05');
  ctx.fillStyle = grad;
  ctx.beginPath();
  ctx.moveTo(tx + a0x, ty + a0y);
  ctx.lineTo(bx + a1x, by + a1y);
  ctx.lineTo(bx - a1x, by - a1y);
  ctx.lineTo(tx - a0x, ty - a0y);
  ctx.closePath();
  ctx.fill();
  ctx.restore();
}

/**
 * Ball in hand: the allowed area tinted, the cue ball's wished place outlined.
 * @param {Ctx} ctx
 * @param {View} view
 * @param {import('./geometry.js').Area} area
 * @param {{x: number, y: number, free: boolean, r: number} | null} pending
 */
export function drawPlacement(ctx, view, area, pending) {
  const [ax0, ay0] = view.toScreen(area.x0, area.y1);
  const [ax1, ay1] = view.toScreen(area.x1, area.y0);
  const [x0, y0, x1, y1] = [Math.min(ax0, ax1), Math.min(ay0, ay1), Math.max(ax0, ax1),
    Math.max(ay0, ay1)];
  ctx.save();
  ctx.fillStyle = 'rgba(255,255,255,0.07)';
  ctx.strokeStyle = 'rgba(255,255,255,0.35)';
  ctx.setLineDash([6, 5]);
  ctx.lineWidth = 1;
  ctx.fillRect(x0, y0, x1 - x0, y1 - y0);
  ctx.strokeRect(x0, y0, x1 - x0, y1 - y0);
  if (pending && !pending.free) {
    const [px, py] = view.toScreen(pending.x, pending.y);
    ctx.setLineDash([]);
    ctx.strokeStyle = 'rgba(255,80,80,0.9)';
    ctx.lineWidth = 2;
    ctx.beginPath();
    ctx.arc(px, py, pending.r * view.scale * 1.1, 0, Math.PI * 2);
    ctx.stroke();
  }
  ctx.restore();
}

/**
 * Calling the 8: pockets ringed, the called one (or the hovered one) bright.
 * @param {Ctx} ctx
 * @param {View} view
 * @param {Table} table
 * @param {number} called pocket index, -1 for none
 * @param {number} hovered pocket index, -1 for none
 * @param {number} pulse 0..1
 */
export function drawPocketCall(ctx, view, table, called, hovered, pulse) {
  ctx.save();
  table.pockets.forEach((p, i) => {
    const [px, py] = view.toScreen(p.center[0], p.center[1]);
    const on = i === called || i === hovered;
    ctx.strokeStyle = on ? 'rgba(255,220,80,0.95)' : `rgba(255,220,80,${0.3 + 0.3 * pulse})`;
    ctx.lineWidth = on ? 3 : 2;
    ctx.beginPath();
    ctx.arc(px, py, p.radius * view.scale * 1.25, 0, Math.PI * 2);
    ctx.stroke();
  });
  ctx.restore();
}

/**
 * Power meter next to the cue ball while pulling back.
 * @param {Ctx} ctx
 * @param {View} view
 * @param {Vec} cue
 * @param {number} power 0..1
 */
export function drawPowerMeter(ctx, view, cue, power) {
  const [x, y] = view.toScreen(cue[0], cue[1]);
  const h = Math.max(40, view.scale * 0.25);
  const w = Math.max(6, view.scale * 0.02);
  const left = x + view.scale * 0.08;
  const top = y - h / 2;
  ctx.save();
  ctx.fillStyle = 'rgba(0,0,0,0.55)';
  ctx.fillRect(left, top, w, h);
  const g = ctx.createLinearGradient(0, top + h, 0, top);
  g.addColorStop(0, '#4ade80');
  g.addColorStop(0.6, '#facc15');
  g.addColorStop(1, '#ef4444');
  ctx.fillStyle = g;
  ctx.fillRect(left, top + h * (1 - power), w, h * power);
  ctx.strokeStyle = 'rgba(255,255,255,0.6)';
  ctx.strokeRect(left, top, w, h);
  ctx.restore();
}

/**
 * The shot clock's last seconds: a red ring around the cue ball that empties as time runs
 * out and pulses, so the shooter sees it where they look.
 * @param {Ctx} ctx
 * @param {View} view
 * @param {Table} table
 * @param {Vec} cue
 * @param {number} left share of the urgent seconds left, 0..1
 * @param {number} pulse 0..1
 */
export function drawClockRing(ctx, view, table, cue, left, pulse) {
  const [x, y] = view.toScreen(cue[0], cue[1]);
  const r = table.ball_radius * view.scale * 2.1;
  ctx.save();
  ctx.lineWidth = Math.max(3, view.scale * 0.008);
  ctx.strokeStyle = 'rgba(0,0,0,0.45)';
  ctx.beginPath();
  ctx.arc(x, y, r, 0, Math.PI * 2);
  ctx.stroke();
  ctx.strokeStyle = `rgba(248,80,80,${0.7 + 0.3 * pulse})`;
  ctx.beginPath();
  ctx.arc(x, y, r, -Math.PI / 2, -Math.PI / 2 + Math.PI * 2 * Math.max(0, Math.min(1, left)));
  ctx.stroke();
  ctx.restore();
}
