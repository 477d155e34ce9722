/**
 * Playback of the server's frame stream at the display's rate.
 *
 * The server streams ball positions and sprite cels at a network rate lower than 60 Hz.
 * The player keeps a short buffer and plays it back a little behind the newest frame
 * (`delay`), interpolating positions linearly and cels along the roll, so motion is smooth
 * and a late packet does not make balls stutter. Pure: no DOM, driven by `advance(dt)`.
 */

/** Cel difference c0 -> c1 (mod n) closest to the roll `expected` (in cels, >= 0). */
export function celStep(c0, c1, n, expected) {
  const base = (((c1 - c0) % n) + n) % n; // 0..n-1
  const k = Math.round((expected - base) / n);
  return base + k * n;
}

/** Interpolated cel between c0 and c1 at fraction f, given the distance rolled. */
export function interpolateCel(c0, c1, f, n, rolled, radius) {
  const expected = (rolled / (2 * Math.PI * radius)) * n;
  const step = celStep(c0, c1, n, expected);
  return ((Math.floor(c0 + step * f + 1e-9) % n) + n) % n;
}

export class FramePlayer {
  /**
   * @param {object} opts
   * @param {number} opts.cels sprite cels per turn (the server's `cels`)
   * @param {number} opts.radius ball radius, metres
   * @param {number} opts.delay seconds played behind the newest frame
   */
  constructor({ cels = 16, radius = 0.028575, delay = 0.1 } = {}) {
    this.cels = cels;
    this.radius = radius;
    this.delay = delay;
    this.frames = []; // [{t, balls: Map id -> {x, y, cel}}] ascending t
    this.time = 0; // playback time on the frames' clock
    this.playing = false;
    this.headings = new Map(); // id -> radians of the last motion (keeps a stopped sprite)
    this.rest = new Map(); // id -> {x, y, cel}: the table at rest
    this.current = new Map();
    this.ended = false;
    this.onTime = null; // t of the newest frame sent at its own time (not `ahead`) ...
    this.sinceOnTime = 0; // ... and the wall time since it came
  }

  /** The table at rest (from a `state`): clears the stream. */
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
  startShot(restBalls = null, t0 = 0) {
    const start = new Map();
    const from = restBalls ? restBalls.map((b) => [b.id, b]) : [...(this.current.size ? this.current : this.rest)];
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
   */
  push(frame) {
    if (frame.last) this.ended = true;
    if (!frame.ahead && (this.onTime === null || frame.t > this.onTime)) {
      this.onTime = frame.t;
      this.sinceOnTime = 0;
    }
    const last = this.frames[this.frames.length - 1];
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

  /** Interpolated balls at playback time t. */
  sampleAt(t) {
    const frames = this.frames;
    let i = 0;
    while (i + 1 < frames.length && frames[i + 1].t <= t) i++;
    const a = frames[i];
    const b = frames[i + 1] ?? a;
    const span = b.t - a.t;
    const f = span > 0 ? Math.min(1, Math.max(0, (t - a.t) / span)) : 0;
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
      this.headings.set(id, pb.heading ?? this.headings.get(id) ?? 0);
      out.set(id, { x, y, cel, heading: this.headings.get(id), speed });
    }
    return out;
  }
}
