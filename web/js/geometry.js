/**
 * Table geometry for the client: the view transform (table metres <-> canvas pixels) and
 * the aiming guide (where the cue ball would first hit a ball or a cushion).
 *
 * Pure functions, no DOM: tested by `node --test web/tests/`.
 * Table coordinates follow the server (SI units, origin bottom-left at the cushion noses,
 * x along the long side, y up); the screen has y down, so the view flips y.
 */

/** @typedef {[number, number]} Vec a point or a direction, table metres */

/**
 * The table as the server describes it (`state.table`, a match's `geometry`).
 * @typedef {object} Table
 * @property {number} length bed length between cushion noses, metres
 * @property {number} width
 * @property {number} ball_radius
 * @property {number} head_string x of the head string
 * @property {Vec} [head_spot]
 * @property {Vec} [foot_spot]
 * @property {string} [style] "pool" or "snooker"
 * @property {Record<string, Vec>} [spots] the named spots (snooker: the colours')
 * @property {{center: Vec, radius: number, start_deg: number, end_deg: number}[]} [arcs] the D
 * @property {{start: Vec, end: Vec, normal: Vec}[]} cushions noses, inward normals
 * @property {{name?: string, center: Vec, radius: number, jaws?: Vec[], outward?: Vec}[]} pockets
 */

/**
 * Table metres <-> CSS pixels on a canvas (see makeView).
 * @typedef {object} View
 * @property {number} scale CSS pixels per metre
 * @property {number} ox
 * @property {number} oy
 * @property {number} width
 * @property {number} height
 * @property {boolean} rotated the table stands on end
 * @property {(x: number, y: number) => Vec} toScreen table metres -> CSS pixels
 * @property {(sx: number, sy: number) => Vec} toTable CSS pixels -> table metres
 * @property {(a: number) => number} screenAngle a table direction as a screen angle (y down)
 */

/**
 * Where a centre may go: a box, and within it a disc when `disc` is given (snooker's D:
 * the half of the disc inside the box).
 * @typedef {{x0: number, y0: number, x1: number, y1: number,
 *   disc?: {cx: number, cy: number, r: number}}} Area
 */

/** Width of the cushion rubber and of the wooden rail, in metres (drawing only). */
export const CUSHION_WIDTH = 0.05;
export const RAIL_WIDTH = 0.1;

/**
 * The transform that fits the whole table (bed, cushions, rails) into a canvas of
 * `width` x `height` CSS pixels with `margin` CSS pixels around it. On a portrait canvas
 * the table stands on end (head at the top) so it stays as large as possible.
 * @param {Table} table
 * @param {number} width
 * @param {number} height
 * @param {number} [margin]
 * @returns {View}
 */
export function makeView(table, width, height, margin = 8) {
  const border = CUSHION_WIDTH + RAIL_WIDTH;
  const totalL = table.length + 2 * border;
  const totalW = table.width + 2 * border;
  /** @type {(w: number, h: number) => number} */
  const fit = (w, h) => Math.max(1e-6, Math.min((w - 2 * margin) / totalL,
    (h - 2 * margin) / totalW));
  const rotated = fit(height, width) > fit(width, height) * 1.15;
  const scale = rotated ? fit(height, width) : fit(width, height);
  const L = table.length;
  const W = table.width;
  if (!rotated) {
    const ox = (width - L * scale) / 2;
    const oy = (height - W * scale) / 2;
    return {
      scale, ox, oy, width, height, rotated,
      /** Table metres -> CSS pixels. */
      toScreen: (x, y) => [ox + x * scale, oy + (W - y) * scale],
      /** CSS pixels -> table metres. */
      toTable: (sx, sy) => [(sx - ox) / scale, W - (sy - oy) / scale],
      /** A table direction (radians) as a screen angle (y down). */
      screenAngle: (a) => -a,
    };
  }
  const ox = (width - W * scale) / 2;
  const oy = (height - L * scale) / 2;
  return {
    scale, ox, oy, width, height, rotated,
    toScreen: (x, y) => [ox + y * scale, oy + x * scale],
    toTable: (sx, sy) => [(sy - oy) / scale, (sx - ox) / scale],
    screenAngle: (a) => Math.PI / 2 - a,
  };
}

/** @type {(ax: number, ay: number, bx: number, by: number) => number} */
export const dist = (ax, ay, bx, by) => Math.hypot(bx - ax, by - ay);

/**
 * Smallest t > eps with |p + t d - c| = r (d a unit vector), or Infinity.
 * @param {number} px
 * @param {number} py
 * @param {number} dx
 * @param {number} dy
 * @param {number} cx
 * @param {number} cy
 * @param {number} r
 * @param {number} [eps]
 */
export function rayCircle(px, py, dx, dy, cx, cy, r, eps = 1e-9) {
  const fx = px - cx;
  const fy = py - cy;
  const b = fx * dx + fy * dy;
  const c = fx * fx + fy * fy - r * r;
  const disc = b * b - c;
  if (disc < 0) return Infinity;
  const s = Math.sqrt(disc);
  const t1 = -b - s;
  if (t1 > eps) return t1;
  // Starting inside (overlapping) counts only if moving away is not the case.
  if (c < 0 && b < 0) return 0;
  return Infinity;
}

/**
 * Where a ball of radius r centred at p moving along unit d first touches a straight
 * cushion (nose from `start` to `end`, inward `normal`): the centre reaches the line offset
 * by r along the normal while its foot lies within the segment. Returns t or Infinity.
 * @param {number} px
 * @param {number} py
 * @param {number} dx
 * @param {number} dy
 * @param {Table['cushions'][number]} cushion
 * @param {number} r
 */
export function rayCushion(px, py, dx, dy, cushion, r) {
  const [nx, ny] = cushion.normal;
  const [sx, sy] = cushion.start;
  const [ex, ey] = cushion.end;
  const approach = dx * nx + dy * ny;
  if (approach >= -1e-12) return Infinity; // moving along or away from the cushion
  const gap = (px - sx) * nx + (py - sy) * ny - r; // distance of the centre to the offset line
  const t = Math.max(0, -gap / approach);
  const hx = px + t * dx - sx;
  const hy = py + t * dy - sy;
  const lx = ex - sx;
  const ly = ey - sy;
  const len2 = lx * lx + ly * ly;
  const u = (hx * lx + hy * ly) / len2;
  return u >= 0 && u <= 1 ? t : Infinity;
}

/**
 * @typedef {object} Guide
 * @property {'ball'|'cushion'|'jaw'|'none'} kind what the cue ball touches first
 * @property {number} t distance to it, metres
 * @property {Vec} contact the cue ball's centre at contact (the ghost ball)
 * @property {number | null} hitId the object ball touched
 * @property {Vec | null} objectDir the object ball's likely direction (line of centres)
 * @property {Vec | null} cueDir the cue ball's direction after contact
 */

/**
 * The aiming guide for a shot from the cue ball at `cue` ([x, y]) at `angle` (radians from
 * +x): the first ball, cushion or jaw it would touch.
 *
 * `balls` is an iterable of {id, x, y} on the table (the cue ball, id 0, is skipped).
 * `objectDir` is the line of centres; `cueDir` the tangent line for a ball (stun), the
 * mirror for a cushion or a jaw; directions are unit [dx, dy] or null.
 * @param {Table} table
 * @param {Iterable<{id: number, x: number, y: number}>} balls
 * @param {Vec} cue
 * @param {number} angle
 * @returns {Guide}
 */
export function castGuide(table, balls, cue, angle) {
  const r = table.ball_radius;
  const [px, py] = cue;
  const dx = Math.cos(angle);
  const dy = Math.sin(angle);
  let t = Infinity;
  /** @type {{kind: 'none'} | {kind: 'ball', id: number, center: Vec}
   *   | {kind: 'cushion', normal: Vec} | {kind: 'jaw', center: Vec}} */
  let hit = { kind: 'none' };
  for (const b of balls) {
    if (b.id === 0) continue;
    const tb = rayCircle(px, py, dx, dy, b.x, b.y, 2 * r);
    if (tb < t) { t = tb; hit = { kind: 'ball', id: b.id, center: [b.x, b.y] }; }
  }
  for (const c of table.cushions) {
    const tc = rayCushion(px, py, dx, dy, c, r);
    if (tc < t) { t = tc; hit = { kind: 'cushion', normal: c.normal }; }
  }
  for (const c of table.cushions) {
    for (const j of [c.start, c.end]) {
      const tj = rayCircle(px, py, dx, dy, j[0], j[1], r);
      if (tj < t) { t = tj; hit = { kind: 'jaw', center: j }; }
    }
  }
  if (hit.kind === 'none') {
    // Heading into a pocket mouth: run to the edge of the bed's bounding box and beyond.
    const tn = rayBox(px, py, dx, dy, -r * 3, -r * 3, table.length + 3 * r, table.width + 3 * r);
    return { kind: 'none', t: tn, contact: [px + tn * dx, py + tn * dy], hitId: null,
      objectDir: null, cueDir: null };
  }
  /** @type {Vec} */
  const contact = [px + t * dx, py + t * dy];
  if (hit.kind === 'ball') {
    const n = unit(hit.center[0] - contact[0], hit.center[1] - contact[1]);
    // Stun shot: the cue ball leaves along the tangent line (nothing if dead straight).
    const along = dx * n[0] + dy * n[1];
    const tx = dx - along * n[0];
    const ty = dy - along * n[1];
    const cueDir = Math.hypot(tx, ty) > 1e-6 ? unit(tx, ty) : null;
    return { kind: 'ball', t, contact, hitId: hit.id, objectDir: n, cueDir };
  }
  const n = hit.kind === 'cushion' ? hit.normal
    : unit(contact[0] - hit.center[0], contact[1] - hit.center[1]);
  const along = dx * n[0] + dy * n[1];
  return { kind: hit.kind, t, contact, hitId: null, objectDir: null,
    cueDir: [dx - 2 * along * n[0], dy - 2 * along * n[1]] };
}

/**
 * Exit distance of a ray starting inside an axis-aligned box (Infinity-safe).
 * @param {number} px
 * @param {number} py
 * @param {number} dx
 * @param {number} dy
 * @param {number} x0
 * @param {number} y0
 * @param {number} x1
 * @param {number} y1
 */
export function rayBox(px, py, dx, dy, x0, y0, x1, y1) {
  let t = Infinity;
  if (dx > 1e-12) t = Math.min(t, (x1 - px) / dx);
  if (dx < -1e-12) t = Math.min(t, (x0 - px) / dx);
  if (dy > 1e-12) t = Math.min(t, (y1 - py) / dy);
  if (dy < -1e-12) t = Math.min(t, (y0 - py) / dy);
  return Math.max(0, t);
}

/**
 * @param {number} x
 * @param {number} y
 * @returns {Vec}
 */
export function unit(x, y) {
  const n = Math.hypot(x, y);
  return n > 0 ? [x / n, y / n] : [0, 0];
}

/**
 * Where the cue ball may be placed with ball in hand: the whole bed ("anywhere") or the
 * kitchen ("behind_head_string": x <= head string). Returns {x0, y0, x1, y1} for the ball
 * centre, or null when there is no ball in hand.
 * @param {Table} table
 * @param {string | null} ballInHand
 * @returns {Area | null}
 */
export function placementArea(table, ballInHand) {
  if (!ballInHand) return null;
  const r = table.ball_radius;
  const d = table.arcs?.[0];
  if (ballInHand === 'in_d' && d) { // snooker: on or within the lines of the D
    const [cx, cy] = d.center;
    return { x0: Math.max(r, cx - d.radius), y0: cy - d.radius, x1: cx, y1: cy + d.radius,
      disc: { cx, cy, r: d.radius } };
  }
  const x1 = ballInHand === 'behind_head_string' ? table.head_string : table.length - r;
  return { x0: r, y0: r, x1, y1: table.width - r };
}

/**
 * Clamp a wished cue-ball position into the allowed area and report whether it overlaps
 * another ball (the server has the last word; this only guides the drag).
 * @param {Table} table
 * @param {Area} area
 * @param {Iterable<{id: number, x: number, y: number}>} balls
 * @param {number} x
 * @param {number} y
 * @returns {{x: number, y: number, free: boolean, clamped: boolean}}
 */
export function placeCue(table, area, balls, x, y) {
  let cx = Math.min(Math.max(x, area.x0), area.x1);
  let cy = Math.min(Math.max(y, area.y0), area.y1);
  const disc = area.disc;
  const off = disc ? dist(cx, cy, disc.cx, disc.cy) : 0;
  if (disc && off > disc.r) { // onto the D's arc, a hair inside
    const k = (disc.r - 1e-6) / off;
    cx = disc.cx + (cx - disc.cx) * k;
    cy = disc.cy + (cy - disc.cy) * k;
  }
  const r = table.ball_radius;
  let free = true;
  for (const b of balls) {
    if (b.id === 0) continue;
    if (dist(cx, cy, b.x, b.y) < 2 * r) { free = false; break; }
  }
  // Held outside the legal area: the ball stays on its edge (and the player is told why).
  const clamped = Math.abs(cx - x) > r * 0.5 || Math.abs(cy - y) > r * 0.5;
  return { x: cx, y: cy, free, clamped };
}

/**
 * Index of the pocket whose hole contains (x, y) (with some slack), or -1.
 * @param {Table} table
 * @param {number} x
 * @param {number} y
 * @param {number} [slack]
 */
export function pocketAt(table, x, y, slack = 1.6) {
  let best = -1;
  let bestD = Infinity;
  table.pockets.forEach((p, i) => {
    const d = dist(x, y, p.center[0], p.center[1]);
    if (d < p.radius * slack && d < bestD) { best = i; bestD = d; }
  });
  return best;
}

/**
 * Aiming by pulling back: the shot angle points from the cue ball towards the pressed point
 * `anchor`; pulling the pointer back (away from the target, along the aim line) sets the
 * power in [0, 1] over `maxPull` metres.
 * @param {Vec} anchor
 * @param {Vec} pointer
 * @param {number} angle
 * @param {number} maxPull
 */
export function pullPower(anchor, pointer, angle, maxPull) {
  const back = -((pointer[0] - anchor[0]) * Math.cos(angle)
    + (pointer[1] - anchor[1]) * Math.sin(angle));
  return Math.min(1, Math.max(0, back / maxPull));
}

/** The softest shot, m/s: the client's choice of the bottom of the power scale. */
export const MIN_SPEED = 0.25;

/**
 * Cue-ball speed in m/s for a power in [0, 1]: gentle at the bottom, the server's fastest
 * shot (`limits.max_speed`) at the top. The curve gives fine control over soft shots.
 * @param {number} power
 * @param {number} maxSpeed
 */
export function speedFromPower(power, maxSpeed) {
  const p = Math.min(1, Math.max(0, power));
  const top = Math.max(MIN_SPEED, maxSpeed);
  return MIN_SPEED + (top - MIN_SPEED) * p ** 1.6;
}

/**
 * Clamp a tip offset (side, height) into the legal disc |tip| <= limit (`limits.max_tip`).
 * @param {number} side
 * @param {number} height
 * @param {number} limit
 * @returns {[number, number]}
 */
export function clampTip(side, height, limit) {
  const n = Math.hypot(side, height);
  if (n <= limit || n === 0) return [side, height];
  return [(side * limit) / n, (height * limit) / n];
}

/**
 * The tip as the server's `shoot` names it (where the tip meets the ball seen from behind
 * at the bed's level) for a tip seen along a cue raised `elevation` radians: the server's
 * `tip_seen_level`. Level, it is the same tip.
 * @param {number} side
 * @param {number} height
 * @param {number} elevation radians
 * @returns {[number, number]}
 */
export function tipSeenLevel(side, height, elevation) {
  if (elevation === 0) return [side, height];
  const depth = Math.sqrt(Math.max(1 - side * side - height * height, 0));
  return [side, Math.sin(elevation) * depth + Math.cos(elevation) * height];
}

/**
 * The inverse of `tipSeenLevel`: a tip as the server names it (seen from behind at the
 * bed's level) seen along a cue raised `elevation` radians.
 * @param {number} side
 * @param {number} height
 * @param {number} elevation radians
 * @returns {[number, number]}
 */
export function tipAlongCue(side, height, elevation) {
  if (elevation === 0) return [side, height];
  const depth = Math.sqrt(Math.max(1 - side * side - height * height, 0));
  return [side, Math.cos(elevation) * height - Math.sin(elevation) * depth];
}

/**
 * How far side spin turns the cue ball off the aim line (radians, positive to the left):
 * the same formula as the server's `Shot.squirt` (Alciatore, TP A-31), with the server's
 * cue mass ratio, so the guide shows the path the ball will take.
 * @param {number} side tip offset, fraction of the radius (right > 0)
 * @param {number} massRatio ball mass over the cue's end mass
 */
export function squirt(side, massRatio) {
  const cos2 = 1 - side * side;
  return Math.atan((2.5 * side * Math.sqrt(cos2)) / (1 + massRatio + 2.5 * cos2));
}

/**
 * Where an object ball sent from `from` along unit `dir` stops being predictable: its
 * centre reaches a cushion, a jaw or another ball, or enters a pocket (it drops). The
 * guide line of the object ball ends there, never across a rail or off the table.
 * `skip` are ball ids ignored (the object ball itself and the cue ball).
 * @param {Table} table
 * @param {Iterable<{id: number, x: number, y: number}>} balls
 * @param {Vec} from
 * @param {Vec} dir
 * @param {number[]} [skip]
 * @returns {{kind: 'cushion' | 'jaw' | 'ball' | 'pocket' | 'none', t: number, end: Vec}}
 */
export function objectPath(table, balls, from, dir, skip = [0]) {
  const r = table.ball_radius;
  const [px, py] = from;
  const [dx, dy] = dir;
  /** @type {'cushion' | 'jaw' | 'ball' | 'pocket' | 'none'} */
  let kind = 'none';
  let t = rayBox(px, py, dx, dy, 0, 0, table.length, table.width);
  for (const c of table.cushions) {
    const tc = rayCushion(px, py, dx, dy, c, r);
    if (tc < t) { t = tc; kind = 'cushion'; }
  }
  for (const c of table.cushions) {
    for (const j of [c.start, c.end]) {
      const tj = rayCircle(px, py, dx, dy, j[0], j[1], r);
      if (tj < t) { t = tj; kind = 'jaw'; }
    }
  }
  for (const p of table.pockets) {
    const tp = rayCircle(px, py, dx, dy, p.center[0], p.center[1], p.radius);
    if (tp < t) { t = tp; kind = 'pocket'; }
  }
  for (const b of balls) {
    if (skip.includes(b.id)) continue;
    const tb = rayCircle(px, py, dx, dy, b.x, b.y, 2 * r);
    if (tb < t) { t = tb; kind = 'ball'; }
  }
  return { kind, t, end: [px + t * dx, py + t * dy] };
}
