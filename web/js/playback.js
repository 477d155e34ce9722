/**
 * Playing a shot back, shared by the live table and the replay (players, spectators, late
 * joiners, reconnecting players, replays: the same code). Each gets the shot's whole motion
 * in one `motion` message at the strike (a replay: from the stored shot), reduced by
 * state.js into effects that a ShotPlayback carries out:
 *
 *  - the balls: evaluated from the motion's exact tracks (track.js) at the playback time,
 *    which runs on this client's clock from where the shot is when the motion arrives (0 at
 *    the strike; a late joiner from the tick its `state` said, plus the time since);
 *  - sounds: each at its own time in the shot, when the playback reaches it;
 *  - pocketed balls: each slides from where it really dropped into its pocket, shrinking
 *    and fading, from the instant it dropped.
 *
 * Pure: no DOM, no audio, driven by `update(dt, now)`; tested with `node --test`.
 * `window.pool.track(t)` (main.js) reads `shownTrack`: what the renderer would draw t s
 * after the strike of the shot being shown (or the last one shown, until the next starts).
 */

import { motionAt, soundHeard } from './track.js';

/** @typedef {import('./track.js').Motion} Motion */
/** @typedef {{x: number, y: number, z?: number, cel: number, heading: number, speed: number}} ShownBall */
/** @typedef {Map<number, ShownBall>} BallMap id -> where to draw the ball now */
/** @typedef {{id: number, x: number, y: number, cel?: number, on_table?: boolean}} RestBall */

// ---- pocketed balls -----------------------------------------------------------------------

/** Seconds a pocketed ball takes to slide into its hole at most (at pace 1). */
export const SINK_SECONDS = 0.18;
/** ... and at least. */
const SINK_MIN = 0.05;

/**
 * @typedef {object} Sinking
 * @property {number} id ball id
 * @property {[number, number]} from where it dropped (metres)
 * @property {[number, number]} to the pocket's centre
 * @property {number} cel
 * @property {number} heading
 * @property {number} start wall time of the drop, seconds
 * @property {number} duration seconds
 */

/**
 * Centre of the pocket nearest to (x, y).
 * @param {import('./geometry.js').Table} table
 * @param {number} x
 * @param {number} y
 * @returns {[number, number]}
 */
export function nearestPocket(table, x, y) {
  let best = table.pockets[0].center;
  let bestD = Infinity;
  for (const p of table.pockets) {
    const d = Math.hypot(p.center[0] - x, p.center[1] - y);
    if (d < bestD) { bestD = d; best = p.center; }
  }
  return best;
}

/**
 * Where and how a sinking ball is drawn at wall time `now`: it slides from where it
 * dropped to the pocket's centre, shrinking and fading.
 * @param {Sinking} sink
 * @param {number} now
 * @returns {{x: number, y: number, f: number, alpha: number, scale: number}}
 */
export function sinkPose(sink, now) {
  const f = Math.min(1, Math.max(0, (now - sink.start) / sink.duration));
  return {
    x: sink.from[0] + (sink.to[0] - sink.from[0]) * f,
    y: sink.from[1] + (sink.to[1] - sink.from[1]) * f,
    f,
    alpha: 1 - f * 0.8,
    scale: 1 - 0.45 * f,
  };
}

// ---- the whole playback ---------------------------------------------------------------

/**
 * @typedef {{kind: 'shot', shot: number, t0: number, balls: RestBall[] | null}
 *   | {kind: 'motion', motion: Motion, t0: number}
 *   | {kind: 'rest', balls: RestBall[]}} PlaybackEffect
 */

/** @type {ShotPlayback | null} the playback that last started a shot on this page */
let shown = null;

/**
 * What the renderer would draw t seconds after the strike of the shot being shown (or the
 * last one shown): [{id, x, y, cel}] in table metres, the balls on the table at t.
 * @param {number} t
 * @returns {{id: number, x: number, y: number, cel: number}[]}
 */
export function shownTrack(t) {
  return shown ? shown.track(t) : [];
}

/**
 * One table's shot playback. The screen feeds it the reducer's effects (`apply`), calls
 * `update` once per display frame and draws `balls` and `sinking.list`; sounds that come
 * due go to `onSound`.
 */
export class ShotPlayback {
  /**
   * @param {object} [opts]
   * @param {number} [opts.cels] sprite cels per turn
   * @param {number} [opts.delay] unused (the motion comes whole: nothing to buffer)
   * @param {(sound: string, speed: number) => void} [opts.onSound]
   */
  constructor({ cels = 16, onSound = () => {} } = {}) {
    this.cels = cels;
    this.onSound = onSound;
    /** @type {import('./geometry.js').Table | null} the pockets */
    this.table = null;
    /** @type {BallMap} the balls as shown now */
    this.balls = new Map();
    /** @type {Map<number, {x: number, y: number, cel: number}>} the table at rest */
    this.rest = new Map();
    /** @type {Map<number, number>} id -> radians of the last motion (a still sprite keeps it) */
    this.headings = new Map();
    /** @type {Motion | null} the shot being shown, or the last one */
    this.motion = null;
    this.time = 0; // seconds since its strike
    this.playing = false;
    this.nextSound = 0; // index of the next sound to play
    /** @type {RestBall[] | null} the table at rest, waiting for the playback to end */
    this.pendingRest = null;
    this.sinking = { list: /** @type {Sinking[]} */ ([]) };
    /** @type {Set<number>} balls whose drop has started */
    this.dropped = new Set();
    this.framesSeen = 0; // motion messages played (the name predates them)
  }

  /**
   * The table the shots are played on (its pockets).
   * @param {import('./geometry.js').Table | null} table
   */
  setTable(table) {
    if (table) this.table = table;
  }

  /**
   * Put `balls` on the cloth at rest now, forgetting any shot, sound or drop under way.
   * @param {RestBall[]} balls
   */
  reset(balls) {
    this.rest = new Map();
    for (const b of balls) {
      if (b.on_table === false) continue;
      this.rest.set(b.id, { x: b.x, y: b.y, cel: b.cel ?? 0 });
    }
    this.playing = false;
    this.pendingRest = null;
    this.sinking.list = [];
    this.balls = this.restBalls();
  }

  /** @returns {BallMap} */
  restBalls() {
    /** @type {BallMap} */
    const out = new Map();
    for (const [id, b] of this.rest) {
      out.set(id, { ...b, heading: this.headings.get(id) ?? 0, speed: 0 });
    }
    return out;
  }

  /**
   * Carry out one of the reducer's effects (state.js); other kinds are ignored.
   * @param {{kind: string} & Record<string, any>} effect
   * @param {number} now wall time, seconds
   */
  apply(effect, now) {
    const e = /** @type {PlaybackEffect} */ (effect);
    switch (e.kind) {
      case 'rest':
        // The table at rest comes when the shot is over on the server: show it once the
        // playback has caught up, not over the balls still rolling.
        if (this.done) this.reset(e.balls);
        else this.pendingRest = e.balls;
        break;
      case 'shot':
        // Joining (or coming back) while a shot is shown: its motion follows; until then
        // the balls as the state has them.
        if (e.balls && !(this.playing && this.motion?.shot === e.shot)) this.reset(e.balls);
        break;
      case 'motion':
        this.start(e.motion, e.t0, now);
        break;
      default:
        break;
    }
  }

  /**
   * Play `motion` from `t0` seconds into the shot.
   * @param {Motion} motion
   * @param {number} t0
   * @param {number} now
   */
  start(motion, t0, now) {
    this.motion = motion;
    this.framesSeen += 1;
    this.pendingRest = null;
    this.sinking.list = [];
    this.dropped = new Set();
    this.time = Math.min(Math.max(0, t0), motion.duration);
    this.playing = true;
    this.nextSound = motion.sounds.findIndex((s) => s.t >= this.time - 1e-9);
    if (this.nextSound < 0) this.nextSound = motion.sounds.length;
    // Balls already down before we joined are not dropped again.
    for (const track of motion.tracks) {
      if (track.pocket !== null && track.t[track.t.length - 1] < this.time) {
        this.dropped.add(track.id);
      }
    }
    shown = this;
    this.balls = this.sample(this.time, now, 1);
    this.playSounds();
  }

  /**
   * What the renderer draws t seconds after the strike of the current (or last) shot.
   * @param {number} t
   * `z`: the height of a flying ball above the bed (m), 0 on it.
   * @returns {{id: number, x: number, y: number, z: number, cel: number}[]}
   */
  track(t) {
    if (!this.motion) {
      return [...this.rest].map(([id, b]) => ({ id, x: b.x, y: b.y, z: 0, cel: b.cel }));
    }
    return motionAt(this.motion, t, this.cels).map((p) => ({ id: p.id, x: p.x, y: p.y,
      z: p.z, cel: p.cel }));
  }

  /**
   * The balls at shot time t; starts the drops the playback has just passed.
   * @param {number} t
   * @param {number} now
   * @param {number} pace
   * @returns {BallMap}
   */
  sample(t, now, pace) {
    const motion = /** @type {Motion} */ (this.motion);
    /** @type {BallMap} */
    const out = new Map();
    for (const pose of motionAt(motion, t, this.cels)) {
      const heading = Number.isNaN(pose.heading) ? this.headings.get(pose.id) ?? 0
        : pose.heading;
      this.headings.set(pose.id, heading);
      out.set(pose.id, { x: pose.x, y: pose.y, z: pose.z, cel: pose.cel, heading,
        speed: pose.speed });
    }
    for (const track of motion.tracks) {
      const last = track.t.length - 1;
      if (track.pocket === null || this.dropped.has(track.id) || t <= track.t[last] + 5e-7) {
        continue;
      }
      this.dropped.add(track.id);
      const pocket = this.table?.pockets[track.pocket]?.center
        ?? (this.table ? nearestPocket(this.table, track.x[last], track.y[last]) : null);
      if (!pocket) continue;
      const from = /** @type {[number, number]} */ ([track.x[last], track.y[last]]);
      const span = last > 0 ? track.t[last] - track.t[last - 1] : 0;
      const speed = span > 0
        ? Math.hypot(track.x[last] - track.x[last - 1], track.y[last] - track.y[last - 1]) / span
        : 0;
      const distance = Math.hypot(pocket[0] - from[0], pocket[1] - from[1]);
      // At the speed it dropped with, into the hole: no pause where it crossed the edge.
      const seconds = Math.min(SINK_SECONDS, Math.max(SINK_MIN, speed > 0 ? distance / speed
        : SINK_SECONDS));
      this.sinking.list.push({ id: track.id, from, to: [pocket[0], pocket[1]],
        cel: out.get(track.id)?.cel ?? 0, heading: this.headings.get(track.id) ?? 0,
        start: now - (t - track.t[last]) / pace, duration: seconds / pace });
    }
    return out;
  }

  playSounds() {
    const motion = this.motion;
    if (!motion) return;
    while (this.nextSound < motion.sounds.length
           && motion.sounds[this.nextSound].t <= this.time + 1e-9) {
      const s = motion.sounds[this.nextSound++];
      this.onSound(soundHeard(motion, s), s.speed);
    }
  }

  /**
   * Move on by `dt` seconds of wall time (`pace` 2: twice as fast) at wall time `now`:
   * advance the shot, start the drops of balls just pocketed, play the sounds due.
   * @param {number} dt
   * @param {number} now
   * @param {number} [pace]
   * @returns {BallMap} the balls to draw
   */
  update(dt, now, pace = 1) {
    if (this.playing && this.motion) {
      this.time = Math.min(this.motion.duration, this.time + dt * pace);
      if (this.time > this.motion.duration - 1e-9) this.time = this.motion.duration;
      this.balls = this.sample(this.time, now, pace);
      this.playSounds();
      if (this.time >= this.motion.duration) this.playing = false;
    }
    if (this.pendingRest && this.done) this.reset(this.pendingRest);
    this.sinking.list = this.sinking.list.filter((s) => now - s.start <= s.duration);
    return this.balls;
  }

  /** True once the shot being played has reached its end (or none plays). */
  get done() { return !this.playing; }

  /** True while a shot is being played. */
  get busy() { return this.playing; }
}
