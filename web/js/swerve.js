/**
 * The path a raised cue sends the cue ball along, alone on the cloth: the engine's own model
 * (server/engine/shot.py `cue_ball_motion`, physics/motion.py), computed here so the aim's
 * guide can curve as the ball will, with nothing asked of the server.
 *
 * A lone ball's motion has closed forms: the strike gives its velocity and spin (Alciatore
 * TP A-30), the downward part bounces it off the slate (restitution 0.5); in the air it flies
 * straight (seen from above) for 2 vz / g; each landing bounces it at half its speed down
 * with the slate's Coulomb friction on the contact's slip; on the cloth the slip keeps its
 * direction, so sliding is a parabola under -u_s g along it, lasting |u| / (7/2 u_s g), and
 * then the ball rolls straight. Pure: no DOM.
 */

import { castGuide, squirt } from './geometry.js';

/** @typedef {import('./geometry.js').Vec} Vec */
/** @typedef {import('./geometry.js').Guide} Guide */

/** The engine's figures (server/engine/params.py, physics/constants.py). */
export const PHYSICS = Object.freeze({
  g: 9.81,
  uSlide: 0.2,
  eSlate: 0.5,
  minHop: 0.1, // m/s: a slower bounce stays on the cloth
});

const SLIDE_SAMPLES = 24; // points along the sliding parabola
const FLIGHT_SAMPLES = 24; // points along a hop (its height: whether it comes down on a ball)
const EPS = 1e-9;

/**
 * One point of the path: where the centre is (table metres) and how high it flies.
 * @typedef {{x: number, y: number, z: number}} PathPoint
 */

/**
 * The cue ball's path until it rolls straight: points from `cue`, then the direction it
 * rolls on. A level shot without side-spin curve is two points and that direction.
 * @param {[number, number]} cue where the cue ball is
 * @param {{angle: number, speed: number, tip: number[], elevation: number}} stroke the
 *   `shoot` message's fields (tip seen from behind at the bed's level, as the server names it)
 * @param {number} radius the ball's radius (m)
 * @param {number} massRatio the server's `limits.cue_mass_ratio`
 * @returns {{points: PathPoint[], dir: [number, number]}}
 */
export function cueBallPath(cue, stroke, radius, massRatio) {
  const ball = strike(stroke, radius, massRatio);
  /** @type {PathPoint[]} */
  const points = [{ x: cue[0], y: cue[1], z: 0 }];
  const p = { x: cue[0], y: cue[1] };
  let vz = hop(ball.down);
  while (vz > 0) {
    fly(p, ball, vz, points);
    vz = land(ball, vz, radius);
  }
  slide(p, ball, radius, points);
  const speed = Math.hypot(ball.vx, ball.vy);
  const last = points[points.length - 1];
  if (last.x !== p.x || last.y !== p.y) points.push({ x: p.x, y: p.y, z: 0 });
  /** @type {[number, number]} */
  const dir = speed > EPS ? [ball.vx / speed, ball.vy / speed]
    : [Math.cos(stroke.angle), Math.sin(stroke.angle)];
  return { points, dir };
}

/**
 * The ball just after the strike: velocity, spin and the speed driven into the bed
 * (the server's `Shot.cue_ball_motion` and `downward_speed`).
 * @param {{angle: number, speed: number, tip: number[], elevation: number}} stroke
 * @param {number} radius
 * @param {number} massRatio
 */
export function strike({ angle, speed, tip, elevation }, radius, massRatio) {
  const alpha = squirt(tip[0], massRatio);
  const ex = Math.cos(angle + alpha);
  const ey = Math.sin(angle + alpha);
  const a = tip[0] * radius;
  const b = tip[1] * radius;
  const c = Math.sqrt(Math.max(radius * radius - a * a - b * b, 0));
  const k = (5 * speed) / (2 * radius * radius);
  const cosT = Math.cos(elevation);
  const sinT = Math.sin(elevation);
  const dx = Math.cos(angle);
  const dy = Math.sin(angle);
  return {
    vx: speed * cosT * ex,
    vy: speed * cosT * ey,
    wx: cosT * k * b * -ey + sinT * k * (a * dx + c * dy),
    wy: cosT * k * b * ex + sinT * k * (a * dy - c * dx),
    down: speed * sinT,
  };
}

/**
 * The speed up a bounce off the slate gives, 0 when too slow to leave it.
 * @param {number} down m/s into the slate
 */
function hop(down) {
  const up = PHYSICS.eSlate * down;
  return up < PHYSICS.minHop ? 0 : up;
}

/**
 * One flight from the bed to the bed: straight seen from above, a parabola in height.
 * @param {{x: number, y: number}} p moved to where it lands
 * @param {{vx: number, vy: number}} ball
 * @param {number} vz up at take-off
 * @param {PathPoint[]} points
 */
function fly(p, ball, vz, points) {
  const { g } = PHYSICS;
  const time = (2 * vz) / g;
  for (let i = 1; i <= FLIGHT_SAMPLES; i++) {
    const t = (time * i) / FLIGHT_SAMPLES;
    points.push({ x: p.x + ball.vx * t, y: p.y + ball.vy * t,
      z: i === FLIGHT_SAMPLES ? 0 : vz * t - 0.5 * g * t * t });
  }
  p.x += ball.vx * time;
  p.y += ball.vy * time;
}

/**
 * A landing: the slate's friction on the slip, then the next hop's speed up (0: it stays).
 * @param {{vx: number, vy: number, wx: number, wy: number}} ball changed in place
 * @param {number} down m/s into the slate
 * @param {number} radius
 */
function land(ball, down, radius) {
  const sx = ball.vx - radius * ball.wy;
  const sy = ball.vy + radius * ball.wx;
  const slip = Math.hypot(sx, sy);
  if (slip > 0) {
    const jf = Math.min(PHYSICS.uSlide * (1 + PHYSICS.eSlate) * down, slip / 3.5) / slip;
    const ax = -jf * sx;
    const ay = -jf * sy;
    ball.vx += ax;
    ball.vy += ay;
    ball.wx += (2.5 * ay) / radius;
    ball.wy += (-2.5 * ax) / radius;
  }
  return hop(down);
}

/**
 * Sliding on the cloth: constant friction against the slip, whose direction holds, until
 * the ball rolls. Samples the parabola into `points`, moves `p` to its end.
 * @param {{x: number, y: number}} p
 * @param {{vx: number, vy: number, wx: number, wy: number}} ball changed in place
 * @param {number} radius
 * @param {PathPoint[]} points
 */
function slide(p, ball, radius, points) {
  const sx = ball.vx - radius * ball.wy;
  const sy = ball.vy + radius * ball.wx;
  const slip = Math.hypot(sx, sy);
  if (slip <= EPS) return;
  const decel = PHYSICS.uSlide * PHYSICS.g;
  const ax = (-decel * sx) / slip;
  const ay = (-decel * sy) / slip;
  const time = slip / (3.5 * decel);
  const x0 = p.x;
  const y0 = p.y;
  const { vx, vy } = ball;
  for (let i = 1; i <= SLIDE_SAMPLES; i++) {
    const t = (time * i) / SLIDE_SAMPLES;
    p.x = x0 + vx * t + 0.5 * ax * t * t;
    p.y = y0 + vy * t + 0.5 * ay * t * t;
    points.push({ x: p.x, y: p.y, z: 0 });
  }
  ball.vx += ax * time;
  ball.vy += ay * time;
  ball.wx = -ball.vy / radius;
  ball.wy = ball.vx / radius;
}

/**
 * Where the path's sideways offset from the aim line is, `distance` metres down that line
 * (linear between points; null when the path never gets that far before rolling straight,
 * then along `dir`).
 * @param {{points: PathPoint[], dir: [number, number]}} path
 * @param {number} angle the aim
 * @param {number} distance metres along the aim line
 * @returns {number} positive to the left of the aim
 */
export function offsetAt(path, angle, distance) {
  const o = path.points[0];
  const ux = Math.cos(angle);
  const uy = Math.sin(angle);
  /** @param {{x: number, y: number}} q */
  const along = (q) => (q.x - o.x) * ux + (q.y - o.y) * uy;
  /** @param {{x: number, y: number}} q */
  const left = (q) => -(q.x - o.x) * uy + (q.y - o.y) * ux;
  const pts = path.points;
  for (let i = 1; i < pts.length; i++) {
    const a0 = along(pts[i - 1]);
    const a1 = along(pts[i]);
    if (a1 >= distance && a1 > a0) {
      const f = (distance - a0) / (a1 - a0);
      return left(pts[i - 1]) + f * (left(pts[i]) - left(pts[i - 1]));
    }
  }
  const end = pts[pts.length - 1];
  const step = path.dir[0] * ux + path.dir[1] * uy;
  const rest = (distance - along(end)) / step;
  return left(end) + rest * (-path.dir[0] * uy + path.dir[1] * ux);
}

/**
 * A guide that may bend: the points the cue ball's centre passes before its last straight
 * run (`bends`, none for a level cue), where that run starts (`from`), and the run's guide
 * up to what it meets first.
 * @typedef {{bends: Vec[], from: Vec, guide: Guide}} CurvedGuide
 */

/**
 * The guide along the curved path of a raised stroke: each piece of `cueBallPath` cast
 * against the table in turn, up to the first thing met. A ball in flight passes over a ball
 * while the centres stay more than 2R apart in three dimensions (the engine's rule), so only
 * a ball it comes down on stops the guide there.
 * @param {any} table
 * @param {{id: number, x: number, y: number}[]} balls
 * @param {Vec} cue
 * @param {{angle: number, speed: number, tip: number[], elevation: number}} stroke
 * @param {number} massRatio
 * @returns {CurvedGuide}
 */
export function curvedGuide(table, balls, cue, stroke, massRatio) {
  const r = table.ball_radius;
  const { points, dir } = cueBallPath(cue, stroke, r, massRatio);
  /** @type {Vec[]} */
  const bends = [];
  for (let i = 1; i < points.length; i++) {
    const a = points[i - 1];
    const b = points[i];
    const length = Math.hypot(b.x - a.x, b.y - a.y);
    if (length < EPS) continue;
    /** @type {Vec} */
    const from = [a.x, a.y];
    const heading = Math.atan2(b.y - a.y, b.x - a.x);
    const inFlight = a.z > 0 || b.z > 0;
    const met = inFlight ? balls.filter((o) => o.id !== 0
      && Math.hypot(b.x - o.x, b.y - o.y) ** 2 + b.z * b.z < 4 * r * r) : balls;
    const guide = castGuide(table, met, from, heading);
    if (guide.kind !== 'none' && guide.t <= length) return { bends, from, guide };
    bends.push(from);
  }
  const end = points[points.length - 1];
  /** @type {Vec} */
  const from = [end.x, end.y];
  return { bends, from, guide: castGuide(table, balls, from, Math.atan2(dir[1], dir[0])) };
}
