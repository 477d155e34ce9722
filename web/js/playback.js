/**
 * Playing a shot back, shared by the live table and the replay: both receive the same
 * `frame` and `event` messages (the replay's come from the server's stored shot, streamed
 * like the live one), reduce them with state.js, and hand the effects to a ShotPlayback.
 *
 *  - FramePlayer: the server streams ball positions and sprite cels at a network rate lower
 *    than the display's. The player keeps a short buffer and plays it back a little behind
 *    the newest frame (`delay`), interpolating positions linearly and cels along the roll,
 *    so motion is smooth and a late packet does not make balls stutter.
 *  - SoundQueue: each table event carries its time `t` in the shot; it waits until the
 *    playback reaches that time, so a click is heard when the balls are seen to touch.
 *  - SinkingBalls: a ball that leaves the stream mid-shot was pocketed; it is drawn sliding
 *    into the nearest hole and fading, rather than vanishing on the cloth.
 *
 * Pure: no DOM, no audio, driven by `update(dt, now)`; tested with `node --test`.
 */

/** @typedef {{x: number, y: number, cel: number, heading: number}} FrameBall */
/** @typedef {{x: number, y: number, cel: number, heading: number, speed: number}} ShownBall */
/** @typedef {Map<number, ShownBall>} BallMap id -> where to draw the ball now */
/** @typedef {{id: number, x: number, y: number, cel?: number, on_table?: boolean}} RestBall */
/**
 * @typedef {object} StreamFrame
 * @property {number} t seconds since the shot started
 * @property {{id: number, x: number, y: number, cel: number}[]} balls metres
 * @property {boolean} [last] the shot's final frame
 * @property {boolean} [ahead] sent early, with an earlier frame
 */

/**
 * Cel difference c0 -> c1 (mod n) closest to the roll `expected` (in cels, >= 0).
 * @param {number} c0
 * @param {number} c1
 * @param {number} n
 * @param {number} expected
 */
export function celStep(c0, c1, n, expected) {
  const base = (((c1 - c0) % n) + n) % n; // 0..n-1
  const k = Math.round((expected - base) / n);
  return base + k * n;
}

/**
 * Interpolated cel between c0 and c1 at fraction f, given the distance rolled.
 * @param {number} c0
 * @param {number} c1
 * @param {number} f
 * @param {number} n
 * @param {number} rolled
 * @param {number} radius
 */
export function interpolateCel(c0, c1, f, n, rolled, radius) {
  const expected = (rolled / (2 * Math.PI * radius)) * n;
  const step = celStep(c0, c1, n, expected);
  return ((Math.floor(c0 + step * f + 1e-9) % n) + n) % n;
}

export class FramePlayer {
  /**
   * @param {object} [opts]
   * @param {number} [opts.cels] sprite cels per turn (the server's `cels`)
   * @param {number} [opts.radius] ball radius, metres (the table's `ball_radius`)
   * @param {number} [opts.delay] seconds played behind the newest frame
   */
  constructor({ cels = 16, radius = 0.028575, delay = 0.1 } = {}) {
    this.cels = cels;
    this.radius = radius;
    this.delay = delay;
    /** @type {{t: number, balls: Map<number, FrameBall>}[]} ascending t */
    this.frames = [];
    this.time = 0; // playback time on the frames' clock
    this.playing = false;
    /** @type {Map<number, number>} id -> radians of the last motion (keeps a stopped sprite) */
    this.headings = new Map();
    /** @type {Map<number, {x: number, y: number, cel: number}>} the table at rest */
    this.rest = new Map();
    /** @type {BallMap} */
    this.current = new Map();
    this.ended = false;
    /** @type {number | null} t of the newest frame sent at its own time (not `ahead`) ... */
    this.onTime = null;
    this.sinceOnTime = 0; // ... and the wall time since it came
  }

  /**
   * The table at rest (from a `state`): clears the stream.
   * @param {RestBall[]} balls
   */
  reset(balls) {
    this.rest = new Map();
    for (const b of balls) {
      if (b.on_table === false) continue;
      this.rest.set(b.id, { x: b.x, y: b.y, cel: b.cel ?? 0 });
    }
    this.frames = [];
    this.playing = false;
    this.ended = false;
    this.current = new Map();
    for (const [id, b] of this.rest) {
      this.current.set(id, { ...b, heading: this.headings.get(id) ?? 0, speed: 0 });
    }
  }

  /**
   * A new shot starts: its stream begins at t = 0 from the balls at rest (so the strike is
   * smooth even though the first streamed frame is a few ticks in); `t0` > 0 when joining
   * a shot already being shown.
   */
  /**
   * @param {RestBall[] | null} [restBalls]
   * @param {number} [t0]
   */
  startShot(restBalls = null, t0 = 0) {
    /** @type {Map<number, FrameBall>} */
    const start = new Map();
    /** @type {[number, {x: number, y: number, cel?: number}][]} */
    const from = restBalls ? restBalls.map((b) => [b.id, b])
      : [...(this.current.size ? this.current : this.rest)];
    for (const [id, b] of from) {
      start.set(id, { x: b.x, y: b.y, cel: b.cel ?? 0, heading: this.headings.get(id) ?? 0 });
    }
    this.frames = [{ t: t0, balls: start }];
    this.playing = false;
    this.ended = false;
    this.onTime = null;
    this.sinceOnTime = 0;
  }

  /** True once playback has reached the shot's last frame. */
  get done() {
    const last = this.frames[this.frames.length - 1];
    return !this.playing || (this.ended && this.time >= last.t - 1e-9);
  }

  /**
   * Append a streamed frame: {t (s), balls: [{id, x, y, cel}] (x, y metres), ahead}.
   * `ahead`: sent early with an earlier frame (several frames a message), so its arrival
   * says nothing about where the stream is now.
   * @param {StreamFrame} frame
   */
  push(frame) {
    if (frame.last) this.ended = true;
    if (!frame.ahead && (this.onTime === null || frame.t > this.onTime)) {
      this.onTime = frame.t;
      this.sinceOnTime = 0;
    }
    const last = this.frames[this.frames.length - 1];
    /** @type {Map<number, FrameBall>} */
    const balls = new Map();
    for (const b of frame.balls) {
      // The direction of travel into this frame (kept when the ball did not move).
      const prev = last?.balls.get(b.id);
      let heading = prev?.heading ?? this.headings.get(b.id) ?? 0;
      if (prev && Math.hypot(b.x - prev.x, b.y - prev.y) > 1e-5) {
        heading = Math.atan2(b.y - prev.y, b.x - prev.x);
      }
      balls.set(b.id, { x: b.x, y: b.y, cel: b.cel, heading });
    }
    if (last && frame.t <= last.t) {
      if (frame.t < last.t - 0.5) { this.frames = []; } else { return; } // new shot / stale
    }
    this.frames.push({ t: frame.t, balls });
    if (!this.playing) {
      this.playing = true;
      this.time = Math.max(this.frames[0].t, frame.t - this.delay);
    }
  }

  /**
   * Where the stream is now (the newest on-time frame plus the wall time since it came, at
   * most the newest frame) minus playback time: how far behind the stream we play. Frames
   * sent ahead do not count, or every message would look like a jump forward.
   */
  get lag() {
    return this.streamNow - this.time;
  }

  get streamNow() {
    const last = this.frames[this.frames.length - 1];
    if (!last) return this.time;
    if (this.onTime === null) return last.t;
    return Math.min(last.t, this.onTime + this.sinceOnTime);
  }

  /**
   * Move playback on by `dt` seconds of wall time (nudged to hold `delay` behind the
   * newest frame) and return the balls now: Map id -> {x, y, cel, heading, speed}.
   * @param {number} dt
   * @returns {BallMap}
   */
  advance(dt) {
    if (!this.playing || this.frames.length === 0) return this.current ?? new Map();
    this.sinceOnTime += dt;
    const lag = this.lag;
    let rate = 1;
    if (lag > this.delay * 4 + 0.25) {
      this.time = this.streamNow - this.delay; // far behind: jump
    } else if (lag > this.delay * 1.5) {
      rate = 1.1;
    } else if (lag < this.delay * 0.5) {
      rate = 0.9;
    }
    this.time += dt * rate;
    const last = this.frames[this.frames.length - 1];
    if (this.time > last.t) this.time = last.t; // hold on the newest frame until more come
    this.current = this.sampleAt(this.time);
    // Drop frames that can no longer be needed.
    while (this.frames.length > 2 && this.frames[1].t <= this.time) this.frames.shift();
    return this.current;
  }

  /**
   * Interpolated balls at playback time t.
   * @param {number} t
   * @returns {BallMap}
   */
  sampleAt(t) {
    const frames = this.frames;
    let i = 0;
    while (i + 1 < frames.length && frames[i + 1].t <= t) i++;
    const a = frames[i];
    const b = frames[i + 1] ?? a;
    const span = b.t - a.t;
    const f = span > 0 ? Math.min(1, Math.max(0, (t - a.t) / span)) : 0;
    /** @type {BallMap} */
    const out = new Map();
    for (const [id, pa] of a.balls) {
      const pb = b.balls.get(id);
      if (!pb) {
        // Pocketed between a and b: it stays visible until b is reached.
        if (f < 1) out.set(id, { ...pa, heading: this.headings.get(id) ?? 0, speed: 0 });
        continue;
      }
      const x = pa.x + (pb.x - pa.x) * f;
      const y = pa.y + (pb.y - pa.y) * f;
      const rolled = Math.hypot(pb.x - pa.x, pb.y - pa.y);
      const cel = interpolateCel(pa.cel, pb.cel, f, this.cels, rolled, this.radius);
      const speed = span > 0 ? rolled / span : 0;
      const heading = pb.heading ?? this.headings.get(id) ?? 0;
      this.headings.set(id, heading);
      out.set(id, { x, y, cel, heading, speed });
    }
    return out;
  }
}

// ---- sounds -----------------------------------------------------------------------------

/** @typedef {{sound: string, speed: number, t: number, shot?: number}} TableSound */
/** @typedef {TableSound & {at: number}} QueuedSound */

/** Seconds of slack when comparing a sound's `t` with the playback time. */
const SOUND_EARLY = 0.01;

export class SoundQueue {
  /**
   * @param {object} [opts]
   * @param {number} [opts.maxWait] seconds a sound waits for the playback to reach its `t`
   *   (frames may come late or not at all: a sound is better late than never) ...
   * @param {number} [opts.maxAge] ... and after which it is dropped unheard (the tab was
   *   asleep: a burst of old clicks would only be noise)
   */
  constructor({ maxWait = 0.6, maxAge = 1.0 } = {}) {
    this.maxWait = maxWait;
    this.maxAge = maxAge;
    /** @type {QueuedSound[]} in arrival order */
    this.items = [];
  }

  /**
   * A table event arrived at wall time `now` (seconds).
   * @param {TableSound} sound
   * @param {number} now
   */
  push(sound, now) {
    this.items.push({ sound: sound.sound, speed: sound.speed, t: sound.t, shot: sound.shot,
      at: now });
  }

  /**
   * Take the sounds due at wall time `now`, in arrival order: those the playback has
   * reached (`time`, seconds into the shot; null when no shot is playing, and then every
   * sound is due), and those that waited `maxWait` already. Sounds older than `maxAge` are
   * dropped rather than returned. `pace` > 1 (a replay played faster) shortens both waits.
   * @param {number} now
   * @param {number | null} time
   * @param {number} [pace]
   * @returns {QueuedSound[]}
   */
  take(now, time, pace = 1) {
    /** @type {QueuedSound[]} */
    const due = [];
    /** @type {QueuedSound[]} */
    const waiting = [];
    for (const s of this.items) {
      const age = now - s.at;
      if (time === null || s.t <= time + SOUND_EARLY || age > this.maxWait / pace) {
        if (age < this.maxAge / pace) due.push(s);
      } else {
        waiting.push(s);
      }
    }
    this.items = waiting;
    return due;
  }

  clear() { this.items = []; }

  get size() { return this.items.length; }
}

// ---- pocketed balls -----------------------------------------------------------------------

/** Seconds a pocketed ball takes to slide into its hole (at pace 1). */
export const SINK_SECONDS = 0.18;

/**
 * @typedef {object} Sinking
 * @property {number} id ball id
 * @property {[number, number]} from where it left the stream (metres)
 * @property {[number, number]} to the pocket's centre
 * @property {number} cel
 * @property {number} heading
 * @property {number} start wall time, seconds
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
 * Where and how a sinking ball is drawn at wall time `now`: it slides from where it was
 * last seen to the pocket's centre, shrinking and fading.
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

export class SinkingBalls {
  /** @param {number} [seconds] */
  constructor(seconds = SINK_SECONDS) {
    this.seconds = seconds;
    /** @type {Sinking[]} */
    this.list = [];
  }

  /**
   * Balls shown in `before` and gone from `after` (one display frame later, while a shot
   * plays) were pocketed: start their drop into the nearest pocket.
   * @param {BallMap} before
   * @param {BallMap} after
   * @param {import('./geometry.js').Table} table
   * @param {number} now
   * @param {number} [pace]
   */
  detect(before, after, table, now, pace = 1) {
    for (const [id, b] of before) {
      if (after.has(id) || this.list.some((s) => s.id === id)) continue;
      this.list.push({ id, from: [b.x, b.y], to: nearestPocket(table, b.x, b.y), cel: b.cel,
        heading: b.heading ?? 0, start: now, duration: this.seconds / pace });
    }
  }

  /**
   * Forget the drops that are over at `now`.
   * @param {number} now
   */
  expire(now) {
    this.list = this.list.filter((s) => now - s.start <= s.duration);
  }

  clear() { this.list = []; }
}

// ---- the whole playback ---------------------------------------------------------------

/**
 * @typedef {{kind: 'shot', balls: RestBall[] | null, t0: number}
 *   | {kind: 'frame', t: number, balls: StreamFrame['balls'], last: boolean, ahead?: boolean}
 *   | ({kind: 'sound'} & TableSound)
 *   | {kind: 'rest', balls: RestBall[]}} PlaybackEffect
 */

/**
 * One table's shot playback: frames, sounds and pocketed balls kept in step. The screen
 * feeds it the reducer's effects (`apply`), calls `update` once per display frame and
 * draws `balls` and `sinking.list`; sounds that come due go to `onSound`.
 */
export class ShotPlayback {
  /**
   * @param {object} [opts]
   * @param {number} [opts.cels] sprite cels per turn
   * @param {number} [opts.delay] seconds played behind the newest frame
   * @param {(sound: string, speed: number) => void} [opts.onSound]
   */
  constructor({ cels = 16, delay = 0.1, onSound = () => {} } = {}) {
    this.player = new FramePlayer({ cels, delay });
    this.sounds = new SoundQueue();
    this.sinking = new SinkingBalls();
    this.onSound = onSound;
    /** @type {import('./geometry.js').Table | null} pockets and ball radius */
    this.table = null;
    /** @type {BallMap} the balls as shown now */
    this.balls = new Map();
    /** @type {RestBall[] | null} the table at rest, waiting for the playback to end */
    this.pendingRest = null;
    this.framesSeen = 0;
  }

  /**
   * The table the shots are played on (its ball radius paces the cels' roll).
   * @param {import('./geometry.js').Table | null} table
   */
  setTable(table) {
    if (!table || table === this.table) return;
    this.table = table;
    this.player.radius = table.ball_radius;
  }

  /**
   * Put `balls` on the cloth at rest now, forgetting any shot, sound or drop under way.
   * @param {RestBall[]} balls
   */
  reset(balls) {
    this.player.reset(balls);
    this.pendingRest = null;
    this.sounds.clear();
    this.sinking.clear();
    this.balls = this.player.current;
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
        // The table at rest comes as soon as the shot is computed: show it once the
        // playback has caught up, not over the balls still rolling.
        if (this.player.done) { this.player.reset(e.balls); this.pendingRest = null; }
        else this.pendingRest = e.balls;
        break;
      case 'shot':
        this.pendingRest = null;
        this.player.startShot(e.balls, e.t0);
        break;
      case 'frame':
        this.framesSeen += 1;
        this.player.push({ t: e.t, balls: e.balls, last: e.last, ahead: e.ahead });
        break;
      case 'sound':
        this.sounds.push(e, now);
        break;
      default:
        break;
    }
  }

  /**
   * Move on by `dt` seconds of wall time (`pace` 2: twice as fast) at wall time `now`:
   * advance the frames, start the drops of balls just pocketed, play the sounds due.
   * @param {number} dt
   * @param {number} now
   * @param {number} [pace]
   * @returns {BallMap} the balls to draw
   */
  update(dt, now, pace = 1) {
    const before = this.balls;
    this.balls = this.player.advance(dt * pace);
    if (this.pendingRest && this.player.done) {
      this.player.reset(this.pendingRest);
      this.pendingRest = null;
      this.balls = this.player.current;
    }
    if (this.player.playing && this.table) {
      this.sinking.detect(before, this.balls, this.table, now, pace);
    }
    this.sinking.expire(now);
    const time = this.player.playing ? this.player.time : null;
    for (const s of this.sounds.take(now, time, pace)) this.onSound(s.sound, s.speed);
    return this.balls;
  }

  /** True once the shot being played has reached its last frame (or none plays). */
  get done() { return this.player.done; }

  /** True while a shot is being played. */
  get busy() { return this.player.playing && !this.player.done; }
}
