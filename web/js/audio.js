/**
 * Sounds of the table, synthesised with Web Audio (no sound files): the cue's strike, the
 * click of two balls, the thump of a cushion, the drop into a pocket. Volume follows the
 * impact speed from the server's `event`. The context starts on the first user gesture
 * (browsers block audio before that); `muted` is remembered by the caller.
 */

/**
 * Gain in [0, 1] for an impact at `speed` m/s (`full` = speed that sounds at full volume).
 * @param {number} speed
 * @param {number} full
 */
export function impactGain(speed, full) {
  if (!(speed > 0)) return 0;
  return Math.min(1, Math.sqrt(speed / full));
}

export class TableAudio {
  constructor() {
    /** @type {AudioContext | null} */
    this.ctx = null;
    /** @type {GainNode | null} */
    this.master = null;
    /** @type {AudioBuffer | null} */
    this.noise = null;
    this.muted = false;
    this.recent = 0; // sounds started in the current 30 ms: caps a burst (the break)
    this.recentAt = 0;
  }

  /** Create/resume the AudioContext; call from a user gesture. */
  unlock() {
    /** @type {typeof AudioContext | undefined} */
    const AC = globalThis.AudioContext || /** @type {any} */ (globalThis).webkitAudioContext;
    if (!AC) return;
    if (!this.ctx) {
      this.ctx = new AC();
      this.master = this.ctx.createGain();
      this.master.gain.value = this.muted ? 0 : 0.8;
      this.master.connect(this.ctx.destination);
      this.noise = makeNoise(this.ctx);
    }
    if (this.ctx.state === 'suspended') this.ctx.resume();
  }

  /** @param {boolean} muted */
  setMuted(muted) {
    this.muted = muted;
    if (this.master) this.master.gain.value = muted ? 0 : 0.8;
  }

  /**
   * The unlocked audio graph; the synthesis below runs only from `play`, after `unlock`.
   * @returns {{ctx: AudioContext, master: GainNode, noise: AudioBuffer}}
   */
  graph() {
    if (!this.ctx || !this.master || !this.noise) throw new Error('audio used before unlock');
    return { ctx: this.ctx, master: this.master, noise: this.noise };
  }

  /**
   * Play a table event: kind "strike" | "jump" (a raised cue's strike that sends the ball
   * off the slate: a sharper, brighter click with the slate's knock under it) | "ball" |
   * "cushion" | "jaw" | "pocket" | "land" (a flying ball back on the slate: a duller thump
   * than a rail's).
   * @param {string} kind
   * @param {number} speed impact speed, m/s
   */
  play(kind, speed) {
    if (!this.ctx || this.muted || this.ctx.state !== 'running') return;
    const now = this.ctx.currentTime;
    if (now - this.recentAt > 0.03) { this.recentAt = now; this.recent = 0; }
    if (++this.recent > 6) return;
    switch (kind) {
      case 'strike': this.strike(now, impactGain(speed, 9)); break;
      case 'jump': this.jump(now, impactGain(speed, 9)); break;
      case 'ball': this.click(now, impactGain(speed, 5)); break;
      case 'cushion': case 'jaw': this.thump(now, impactGain(speed, 4)); break;
      case 'pocket': this.drop(now, 0.6 + 0.4 * impactGain(speed, 3)); break;
      case 'land': this.thump(now, 0.6 * impactGain(speed, 3)); break;
      default: break;
    }
  }

  /** The shot clock's tick, once a second in its last seconds. */
  tick() {
    if (!this.ctx || this.muted || this.ctx.state !== 'running') return;
    this.tone(this.ctx.currentTime, 1900, 1600, 0.22, 0.035, 'square');
  }

  /**
   * A gain node rising to `peak` in `attack` s and dying away over `decay` s.
   * @param {number} t
   * @param {number} peak
   * @param {number} attack
   * @param {number} decay
   */
  envelope(t, peak, attack, decay) {
    const { ctx, master } = this.graph();
    const g = ctx.createGain();
    g.gain.setValueAtTime(0.0001, t);
    g.gain.exponentialRampToValueAtTime(Math.max(0.0002, peak), t + attack);
    g.gain.exponentialRampToValueAtTime(0.0001, t + attack + decay);
    g.connect(master);
    return g;
  }

  /**
   * @param {number} t
   * @param {number} freq
   * @param {number} endFreq
   * @param {number} peak
   * @param {number} decay
   * @param {OscillatorType} [type]
   */
  tone(t, freq, endFreq, peak, decay, type = 'sine') {
    const o = this.graph().ctx.createOscillator();
    o.type = type;
    o.frequency.setValueAtTime(freq, t);
    o.frequency.exponentialRampToValueAtTime(endFreq, t + decay);
    o.connect(this.envelope(t, peak, 0.002, decay));
    o.start(t);
    o.stop(t + decay + 0.05);
  }

  /**
   * @param {number} t
   * @param {BiquadFilterType} filterType
   * @param {number} freq
   * @param {number} q
   * @param {number} peak
   * @param {number} decay
   */
  burst(t, filterType, freq, q, peak, decay) {
    const { ctx, noise } = this.graph();
    const src = ctx.createBufferSource();
    src.buffer = noise;
    const f = ctx.createBiquadFilter();
    f.type = filterType;
    f.frequency.value = freq;
    f.Q.value = q;
    src.connect(f);
    f.connect(this.envelope(t, peak, 0.001, decay));
    src.start(t, Math.random() * 0.3);
    src.stop(t + decay + 0.05);
  }

  /**
   * Leather tip on phenolic: a dull tock with a short bright edge.
   * @param {number} t start, AudioContext seconds
   * @param {number} g gain
   */
  strike(t, g) {
    this.tone(t, 420, 180, 0.5 * g + 0.05, 0.05, 'triangle');
    this.burst(t, 'bandpass', 2200, 1.2, 0.35 * g + 0.03, 0.03);
  }

  /**
   * A jump's strike: the tip's sharp crack and, under it, the ball knocking the slate.
   * @param {number} t
   * @param {number} g
   */
  jump(t, g) {
    this.burst(t, 'highpass', 4500, 0.9, 0.45 * g + 0.08, 0.012);
    this.tone(t, 2400, 1500, 0.3 * g + 0.04, 0.02, 'triangle');
    this.tone(t + 0.004, 160, 90, 0.35 * g + 0.05, 0.05, 'sine');
  }

  /**
   * Ball on ball: a hard, high click.
   * @param {number} t
   * @param {number} g
   */
  click(t, g) {
    this.tone(t, 3100 + 400 * g, 2600, 0.45 * g, 0.025, 'sine');
    this.burst(t, 'highpass', 3500, 0.8, 0.5 * g, 0.018);
  }

  /**
   * Ball on cushion: a low rubbery thump.
   * @param {number} t
   * @param {number} g
   */
  thump(t, g) {
    this.tone(t, 140, 70, 0.6 * g, 0.09, 'sine');
    this.burst(t, 'lowpass', 600, 0.7, 0.25 * g, 0.06);
  }

  /**
   * Into the pocket: a knock on the liner and a short rattle.
   * @param {number} t
   * @param {number} g
   */
  drop(t, g) {
    this.tone(t, 220, 90, 0.5 * g, 0.12, 'triangle');
    for (let k = 1; k <= 3; k++) {
      this.burst(t + 0.05 * k + 0.01 * k * k, 'bandpass', 900 - 150 * k, 2, (0.3 * g) / k, 0.04);
    }
  }
}

/**
 * Half a second of white noise, the source of every burst.
 * @param {AudioContext} ctx
 */
function makeNoise(ctx) {
  const len = ctx.sampleRate * 0.5;
  const buf = ctx.createBuffer(1, len, ctx.sampleRate);
  const data = buf.getChannelData(0);
  let seed = 12345;
  for (let i = 0; i < len; i++) {
    seed = (seed * 1103515245 + 12345) & 0x7fffffff; // own tiny PRNG: reproducible
    data[i] = (seed / 0x3fffffff) - 1;
  }
  return buf;
}
