/**
 * A shot's motion: the binary `motion` message (docs/protocol.md) decoded, and evaluated at
 * any instant of the shot. The server sends the whole shot at the strike: per ball, knots
 * (time, position, rolled angle) at every one of its contacts and wherever a straight line
 * would stray more than a fraction of a millimetre from the engine's path; between knots
 * the ball moves in a straight line at constant speed, which is how the engine moves it
 * within a sub-step. So a ball is drawn touching the rail or the ball it hits at the
 * contact's exact time, and its sprite turns with the real roll and stops with the ball.
 *
 * Pure: no DOM; tested with `node --test` and fed the server's real messages by
 * bench/fidelity.py.
 */

export const MOTION_KIND = 1;
export const MOTION_VERSION = 1;
export const MOTION_VERSION_HEIGHTS = 2; // a ball flies: every knot has its height
const OFF_TABLE = 254; // version 2: the ball flies off the table at its last knot
const HEADER_BYTES = 17;
const PER_METRE = 1e4; // positions in 0.1 mm
const PER_SECOND = 1e6; // times in microseconds
const HALF_TICK = 0.5 / PER_SECOND; // a time's rounding
const PHASE_STEPS = 4096; // per turn
const NO_BALL = 255;
export const SOUND_KINDS = ['strike', 'ball', 'cushion', 'jaw', 'pocket', 'land'];

/**
 * @typedef {object} Track one ball's knots (typed arrays of the same length, time order)
 * @property {number} id
 * @property {number | null} pocket the pocket it drops into at its last knot, or null
 * @property {Float64Array} t seconds since the strike
 * @property {Float64Array} x metres
 * @property {Float64Array} y metres
 * @property {Float64Array} phase radians rolled
 * @property {Float64Array} z metres above the bed's resting height (all 0 in version 1)
 * @property {boolean} offTable it flies off the table at its last knot
 * @property {Float64Array} heading direction of travel after each knot (NaN: not moved yet)
 */
/** @typedef {{t: number, kind: string, ids: number[], speed: number, target: number}} Sound */
/**
 * @typedef {object} Motion
 * @property {'motion'} type
 * @property {number} seq
 * @property {number} shot
 * @property {number} duration seconds from the strike to the last tick
 * @property {Track[]} tracks
 * @property {Sound[]} sounds time order
 */
/** @typedef {{id: number, x: number, y: number, z: number, cel: number, heading: number, speed: number}} Pose */

/**
 * What a sound is heard as: a strike that sends its ball off the slate (a raised cue's
 * jump or hop: the ball is above the bed before its first landing) is a 'jump', the sharp
 * click of the tip driving the ball into the slate; every other sound keeps its kind.
 * @param {Motion} motion
 * @param {Sound} sound
 * @returns {string}
 */
export function soundHeard(motion, sound) {
  if (sound.kind !== 'strike') return sound.kind;
  const id = sound.ids[0];
  const landing = motion.sounds.find((s) => s.kind === 'land' && s.ids[0] === id);
  const track = motion.tracks.find((tr) => tr.id === id);
  if (!landing || !track) return sound.kind;
  for (let k = 0; k < track.t.length && track.t[k] <= landing.t; k++) {
    if (track.z[k] > 0) return 'jump';
  }
  return sound.kind;
}

/**
 * Decode a `motion` message.
 * @param {ArrayBuffer | Uint8Array} data
 * @returns {Motion}
 */
export function decodeMotion(data) {
  const bytes = data instanceof Uint8Array ? data : new Uint8Array(data);
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  const version = bytes[1];
  if (bytes.length < HEADER_BYTES || bytes[0] !== MOTION_KIND
    || (version !== MOTION_VERSION && version !== MOTION_VERSION_HEIGHTS)) {
    throw new Error('not a motion message');
  }
  const heights = version === MOTION_VERSION_HEIGHTS;
  let at = HEADER_BYTES;
  const varint = () => {
    let value = 0;
    let scale = 1;
    for (;;) {
      if (at >= bytes.length) throw new Error('truncated motion message');
      const b = bytes[at++];
      value += (b & 127) * scale;
      if (b < 128) return value;
      scale *= 128;
    }
  };
  const zigzag = () => {
    const v = varint();
    return v % 2 ? -(v + 1) / 2 : v / 2;
  };
  const balls = bytes[14];
  const count = view.getUint16(15, true);
  /** @type {Track[]} */
  const tracks = [];
  for (let b = 0; b < balls; b++) {
    const id = bytes[at];
    const pocket = bytes[at + 1];
    const knots = view.getUint16(at + 2, true);
    at += 4;
    const t = new Float64Array(knots);
    const x = new Float64Array(knots);
    const y = new Float64Array(knots);
    const phase = new Float64Array(knots);
    const z = new Float64Array(knots);
    let ti = varint();
    let xi = view.getInt16(at, true);
    let yi = view.getInt16(at + 2, true);
    let pi = view.getUint16(at + 4, true);
    at += 6;
    let zi = 0;
    if (heights) {
      zi = view.getUint16(at, true);
      at += 2;
    }
    for (let k = 0; k < knots; k++) {
      if (k > 0) {
        ti += varint();
        xi += zigzag();
        yi += zigzag();
        pi += zigzag();
        if (heights) zi += zigzag();
      }
      t[k] = ti / PER_SECOND;
      x[k] = xi / PER_METRE;
      y[k] = yi / PER_METRE;
      phase[k] = (pi / PHASE_STEPS) * 2 * Math.PI;
      z[k] = zi / PER_METRE;
    }
    const offTable = heights && pocket === OFF_TABLE;
    tracks.push({ id, pocket: pocket === NO_BALL || offTable ? null : pocket, t, x, y, phase,
      z, offTable, heading: headings(x, y) });
  }
  /** @type {Sound[]} */
  const sounds = [];
  let time = 0;
  for (let e = 0; e < count; e++) {
    time += varint();
    const [kind, a, b, target] = [bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]];
    const speed = view.getUint16(at + 4, true);
    at += 6;
    sounds.push({ t: time / PER_SECOND, kind: SOUND_KINDS[kind] ?? 'ball',
      ids: b === NO_BALL ? [a] : [a, b], speed: speed / 1000,
      target: target === NO_BALL ? -1 : target });
  }
  if (at !== bytes.length) throw new Error('trailing bytes after the motion message');
  return { type: 'motion', seq: view.getUint32(2, true), shot: view.getUint32(6, true),
    duration: view.getUint32(10, true) / PER_SECOND, tracks, sounds };
}

/**
 * Direction of travel after each knot: a still stretch keeps the one before it, NaN before
 * the ball first moves (the sprite keeps the heading it had).
 * @param {Float64Array} x
 * @param {Float64Array} y
 */
function headings(x, y) {
  const out = new Float64Array(x.length);
  let h = NaN;
  for (let k = 0; k < x.length; k++) {
    if (k + 1 < x.length && (x[k + 1] !== x[k] || y[k + 1] !== y[k])) {
      h = Math.atan2(y[k + 1] - y[k], x[k + 1] - x[k]);
    }
    out[k] = h;
  }
  return out;
}

/**
 * The bytes of a base64 text (a replay's `motion` line carries its message so).
 * @param {string} text
 */
export function base64Bytes(text) {
  const raw = atob(text);
  const out = new Uint8Array(raw.length);
  for (let i = 0; i < raw.length; i++) out[i] = raw.charCodeAt(i);
  return out;
}

/**
 * The index of the last knot at or before t (0 before the first).
 * @param {Float64Array} times
 * @param {number} t
 */
function knotBefore(times, t) {
  let lo = 0;
  let hi = times.length - 1;
  if (t >= times[hi]) return hi;
  while (lo < hi) {
    const mid = (lo + hi + 1) >> 1;
    if (times[mid] <= t) lo = mid; else hi = mid - 1;
  }
  return lo;
}

/**
 * Where a ball is at time t (seconds since the strike), or null once it has dropped.
 * @param {Track} track
 * @param {number} t
 * @param {number} [cels] sprite cels per turn
 * @returns {Pose | null}
 */
export function trackAt(track, t, cels = 16) {
  const { t: times, x, y, phase, z } = track;
  const last = times.length - 1;
  // A dropped ball (or one that flew off the table) is on the table up to its last knot,
  // within the time unit.
  const leaves = track.pocket !== null || track.offTable;
  if (leaves && t > times[last] + HALF_TICK) return null;
  const i = knotBefore(times, t);
  let px = x[i];
  let py = y[i];
  let pz = z ? z[i] : 0;
  let ph = phase[i];
  let speed = 0;
  if (i < last && t > times[i]) {
    const span = times[i + 1] - times[i];
    const f = span > 0 ? (t - times[i]) / span : 1;
    px += (x[i + 1] - x[i]) * f;
    py += (y[i + 1] - y[i]) * f;
    if (z) pz += (z[i + 1] - z[i]) * f;
    ph += (phase[i + 1] - phase[i]) * f;
    speed = span > 0 ? Math.hypot(x[i + 1] - x[i], y[i + 1] - y[i]) / span : 0;
  }
  return { id: track.id, x: px, y: py, z: pz, cel: celOf(ph, cels),
    heading: track.heading[i], speed };
}

/**
 * The sprite cel of a rolled angle.
 * @param {number} phase radians
 * @param {number} cels per turn
 */
export function celOf(phase, cels) {
  const turns = phase / (2 * Math.PI);
  return Math.floor((turns - Math.floor(turns)) * cels) % cels;
}

/**
 * Every ball on the table at time t.
 * @param {Motion} motion
 * @param {number} t
 * @param {number} [cels]
 * @returns {Pose[]}
 */
export function motionAt(motion, t, cels = 16) {
  /** @type {Pose[]} */
  const out = [];
  for (const track of motion.tracks) {
    const pose = trackAt(track, t, cels);
    if (pose) out.push(pose);
  }
  return out;
}
