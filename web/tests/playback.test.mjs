import { test } from 'node:test';
import assert from 'node:assert/strict';
import {
  FramePlayer, celStep, interpolateCel, SoundQueue, SinkingBalls, ShotPlayback, sinkPose,
  nearestPocket, SINK_SECONDS,
} from '../js/playback.js';
import { initialState, reduce } from '../js/state.js';
import { TABLE } from './fixtures.mjs';

const R = 0.028575;

/**
 * Ball `id` of a playback result, which the test expects to be there.
 * @param {import('../js/playback.js').BallMap} balls
 * @param {number} id
 */
function one(balls, id) {
  const b = balls.get(id);
  assert.ok(b, `ball ${id} is shown`);
  return b;
}
/**
 * A streamed frame at `t` from rows [id, x, y, cel] (metres).
 * @param {number} t
 * @param {number[][]} balls
 * @param {boolean} [last]
 */
const frame = (t, balls, last = false) => ({ t, last,
  balls: balls.map(([id, x, y, cel]) => ({ id, x, y, cel })) });

test('cel steps follow the distance rolled, across the wrap', () => {
  assert.equal(celStep(14, 2, 16, 4), 4); // wrapped forward
  assert.equal(celStep(3, 3, 16, 16), 16); // one whole turn in one frame
  assert.equal(celStep(3, 3, 16, 0), 0); // at rest
  assert.equal(celStep(5, 4, 16, 15), 15);
  const turnPerCel = (2 * Math.PI * R) / 16;
  assert.equal(interpolateCel(14, 2, 0.5, 16, 4 * turnPerCel, R), 0);
});

test('playback interpolates positions between frames, behind the newest one', () => {
  const p = new FramePlayer({ delay: 0.1 });
  p.reset([{ id: 0, x: 0.5, y: 0.5 }, { id: 1, x: 1.5, y: 0.5 }]);
  p.startShot();
  p.push(frame(0.05, [[0, 0.55, 0.5, 1], [1, 1.5, 0.5, 0]]));
  p.push(frame(0.1, [[0, 0.6, 0.5, 3], [1, 1.5, 0.5, 0]]));
  p.push(frame(0.15, [[0, 0.65, 0.5, 5], [1, 1.5, 0.5, 0]]));
  let balls = p.advance(0); // starts `delay` behind the first frame received: t = 0
  assert.ok(Math.abs(one(balls, 0).x - 0.5) < 1e-12);
  balls = p.advance(0.075);
  assert.ok(one(balls, 0).x > 0.55 && one(balls, 0).x < 0.65, `x=${one(balls, 0).x}`);
  assert.equal(one(balls, 1).x, 1.5);
  assert.ok(Math.abs(one(balls, 0).heading) < 1e-9, 'rolling along +x');
});

test('playback holds on the newest frame when the stream stalls, then resumes', () => {
  const p = new FramePlayer({ delay: 0.1 });
  p.reset([{ id: 0, x: 0, y: 0 }]);
  p.startShot();
  p.push(frame(0.05, [[0, 0.1, 0, 0]]));
  for (let i = 0; i < 30; i++) p.advance(1 / 60);
  assert.equal(one(p.current, 0).x, 0.1);
  p.push(frame(0.1, [[0, 0.2, 0, 0]]));
  const before = one(p.current, 0).x;
  const after = one(p.advance(1 / 60), 0).x;
  assert.ok(after >= before);
});

test('playback far behind jumps to hold only `delay` behind the newest frame', () => {
  const p = new FramePlayer({ delay: 0.1 });
  p.reset([{ id: 0, x: 0, y: 0 }]);
  p.startShot();
  for (let k = 1; k <= 60; k++) p.push(frame(k * 0.05, [[0, k * 0.01, 0, 0]]));
  p.advance(1 / 60);
  assert.ok(p.lag <= 0.1 + 1e-9, `lag ${p.lag}`);
});

test('a ball missing from the next frame was pocketed: shown until then, gone after', () => {
  const p = new FramePlayer({ delay: 0 });
  p.reset([{ id: 0, x: 0, y: 0 }, { id: 3, x: 1, y: 1 }]);
  p.startShot();
  p.push(frame(0.05, [[0, 0.1, 0, 0], [3, 1.02, 1.0, 0]]));
  p.push(frame(0.1, [[0, 0.2, 0, 0]], true));
  let balls = p.advance(0.01);
  assert.ok(balls.has(3));
  for (let i = 0; i < 10; i++) balls = p.advance(0.02);
  assert.ok(!balls.has(3));
  assert.ok(p.done, 'reached the last frame');
});

test('a stopped ball keeps its cel and its heading', () => {
  const p = new FramePlayer({ delay: 0 });
  p.reset([{ id: 0, x: 0, y: 0 }]);
  p.startShot();
  p.push(frame(0.05, [[0, 0, 0.1, 7]]));
  p.push(frame(0.1, [[0, 0, 0.1, 7]], true));
  const balls = p.advance(0.2);
  assert.equal(one(balls, 0).cel, 7);
  assert.ok(Math.abs(one(balls, 0).heading - Math.PI / 2) < 1e-9, 'last moved along +y');
  p.reset([{ id: 0, x: 0, y: 0.1, cel: 7 }]);
  assert.equal(one(p.current, 0).cel, 7);
  assert.ok(Math.abs(one(p.current, 0).heading - Math.PI / 2) < 1e-9);
});

test('joining a shot mid-stream starts from the state`s tick', () => {
  const p = new FramePlayer({ delay: 0.1 });
  p.startShot([{ id: 0, x: 1, y: 0.5, cel: 2 }], 1.0);
  p.push(frame(1.05, [[0, 1.1, 0.5, 4]]));
  const balls = p.advance(0.05);
  assert.ok(one(balls, 0).x >= 1 && one(balls, 0).x <= 1.1);
});

test('frames sent ahead (four a message) play at real-time speed, `delay` behind', () => {
  // The server's stream: a frame every 0.05 s, sent four to a message (one on time, three
  // ahead) every 0.2 s. Playback must run at speed 1 and never run dry between messages.
  const p = new FramePlayer({ delay: 0.1 });
  p.reset([{ id: 0, x: 0, y: 0 }]);
  p.startShot();
  const step = 1 / 60;
  let wall = 0;
  let next = 1; // index of the next frame to send
  const behind = [];
  for (let i = 0; i < 180; i++) { // 3 s of display
    while (next * 0.05 <= wall + 1e-9 && next <= 60) {
      for (let k = 0; k < 4 && next + k <= 60; k++) {
        const t = (next + k) * 0.05;
        p.push({ t, ahead: k > 0, last: next + k === 60, balls: [{ id: 0, x: t, y: 0, cel: 0 }] });
      }
      next += 4;
    }
    const x = one(p.advance(step), 0).x;
    wall += step;
    if (wall > 0.5) behind.push(wall - x); // playback time = x in this stream
  }
  const mean = behind.reduce((a, b) => a + b, 0) / behind.length;
  assert.ok(Math.abs(mean - 0.1) < 0.03, `mean delay ${mean}`);
  assert.ok(Math.max(...behind) - Math.min(...behind) < 0.05, 'no stutter or sawtooth');
});

// ---- the sound queue ----------------------------------------------------------------------

/** @type {(name: string, t: number) => import('../js/playback.js').TableSound} */
const sound = (name, t) => ({ sound: name, speed: 1, t });

test('a sound waits until the playback reaches its time, then plays once', () => {
  const q = new SoundQueue();
  q.push(sound('ball', 0.2), 10);
  assert.deepEqual(q.take(10.05, 0.1), []);
  assert.equal(q.size, 1);
  const due = q.take(10.1, 0.195); // within the 10 ms of slack
  assert.deepEqual(due.map((s) => s.sound), ['ball']);
  assert.equal(due[0].at, 10);
  assert.deepEqual(q.take(10.2, 0.3), [], 'taken once');
});

test('sounds come out in the order they came, each at its own time', () => {
  const q = new SoundQueue();
  // One event message with `also`: strike, ball, cushion at their own times in the shot.
  for (const s of [sound('strike', 0), sound('ball', 0.08), sound('cushion', 0.16)]) q.push(s, 0);
  /** @type {{name: string, time: number}[]} */
  const heard = [];
  for (let k = 0; k <= 30; k++) {
    const time = k / 100; // playback at 1x, from the strike
    for (const s of q.take(k / 100, time)) heard.push({ name: s.sound, time });
  }
  assert.deepEqual(heard.map((h) => h.name), ['strike', 'ball', 'cushion']);
  /** @type {Record<string, number>} */
  const due = { strike: 0, ball: 0.08, cushion: 0.16 };
  for (const { name, time } of heard) {
    assert.ok(time >= due[name] - 0.01 && time <= due[name] + 0.011, `${name} at ${time}`);
  }
});

test('with no shot playing every sound is due at once', () => {
  const q = new SoundQueue();
  q.push(sound('cushion', 3), 0);
  q.push(sound('ball', 5), 0);
  assert.deepEqual(q.take(0, null).map((s) => s.sound), ['cushion', 'ball']);
});

test('a sound whose frames do not come plays after maxWait; a stale one is dropped', () => {
  const q = new SoundQueue({ maxWait: 0.6, maxAge: 1.0 });
  q.push(sound('ball', 5), 0);
  assert.deepEqual(q.take(0.5, 0), []);
  assert.deepEqual(q.take(0.61, 0).map((s) => s.sound), ['ball']);
  q.push(sound('jaw', 5), 0);
  assert.deepEqual(q.take(1.2, 0), [], 'the tab slept: the old click is not played');
  assert.equal(q.size, 0, '... and not kept either');
});

test('a replay played faster waits proportionally less', () => {
  const q = new SoundQueue({ maxWait: 0.6, maxAge: 1.0 });
  q.push(sound('ball', 5), 0);
  assert.deepEqual(q.take(0.25, 0, 2), []);
  assert.equal(q.take(0.31, 0, 2).length, 1);
  q.push(sound('ball', 5), 0);
  assert.deepEqual(q.take(0.26, 0, 4), [], 'older than maxAge / pace');
});

// ---- pocketed balls -----------------------------------------------------------------------

test('the nearest pocket of a point', () => {
  assert.deepEqual(nearestPocket(TABLE, 2.5, 1.25), TABLE.pockets[3].center);
  assert.deepEqual(nearestPocket(TABLE, 1.25, 0.02), TABLE.pockets[1].center);
});

test('a sinking ball slides into the hole, shrinking and fading, over its duration', () => {
  const sink = { id: 3, from: /** @type {[number, number]} */ ([1, 1]),
    to: /** @type {[number, number]} */ ([2, 3]), cel: 0, heading: 0, start: 10,
    duration: 0.2 };
  const at = (/** @type {number} */ now) => sinkPose(sink, now);
  assert.deepEqual(at(10), { x: 1, y: 1, f: 0, alpha: 1, scale: 1 });
  const mid = at(10.1);
  assert.ok(Math.abs(mid.x - 1.5) < 1e-9 && Math.abs(mid.y - 2) < 1e-9);
  assert.ok(Math.abs(mid.alpha - 0.6) < 1e-9 && Math.abs(mid.scale - 0.775) < 1e-9);
  const end = at(10.2);
  assert.ok(Math.abs(end.x - 2) < 1e-9 && Math.abs(end.alpha - 0.2) < 1e-9);
  assert.deepEqual(at(11), at(10.5), 'held at the hole after the end');
  assert.equal(at(11).f, 1);
  assert.deepEqual(at(9), at(10), 'and at the start before it');
});

test('a ball gone from the stream starts one drop, which ends after SINK_SECONDS', () => {
  const sinking = new SinkingBalls();
  /** @type {(x: number, y: number) => import('../js/playback.js').ShownBall} */
  const ball = (x, y) => ({ x, y, cel: 5, heading: 1, speed: 1 });
  const before = new Map([[0, ball(1, 0.6)], [3, ball(2.5, 1.25)]]);
  const after = new Map([[0, ball(1.1, 0.6)]]);
  sinking.detect(before, after, TABLE, 7);
  sinking.detect(before, after, TABLE, 7.01); // seen again: not a second drop
  assert.equal(sinking.list.length, 1);
  const s = sinking.list[0];
  assert.deepEqual([s.id, s.from, s.to, s.cel, s.heading, s.start, s.duration],
    [3, [2.5, 1.25], TABLE.pockets[3].center, 5, 1, 7, SINK_SECONDS]);
  sinking.expire(7 + SINK_SECONDS * 0.99);
  assert.equal(sinking.list.length, 1);
  sinking.expire(7 + SINK_SECONDS * 1.01);
  assert.equal(sinking.list.length, 0);
  sinking.detect(before, after, TABLE, 8, 2);
  assert.equal(sinking.list[0].duration, SINK_SECONDS / 2, 'faster replay, faster drop');
});

// ---- the whole playback, fed by the reducer -----------------------------------------------

const mm = (/** @type {number} */ x) => Math.round(x * 1000);
/** @type {(seq: number, balls: number[][], phase?: string) => object} */
const stateMsg = (seq, balls, phase = 'aiming') => ({ type: 'state', seq, phase, table: TABLE,
  balls, shot: null, clock: null, grace: [], match: null, room: null });
/** A shot: the cue ball rolls along +x, ball 3 near the top-right corner drops at t = 0.1. */
const SHOT = [
  { type: 'welcome', seat: 0, role: 'player', seq: 1, tick_hz: 120, frame_every: 6 },
  stateMsg(1, [[0, 635, 635, 0], [3, mm(2.49), mm(1.22), 0]]),
  { type: 'frame', seq: 2, shot: 1, tick: 6, b: [[0, 700, 635, 2], [3, mm(2.5), mm(1.23), 1]] },
  { type: 'event', seq: 3, shot: 1, tick: 9, t: 0.075, kind: 'pocket', speed: 1, ids: [3] },
  { type: 'frame', seq: 4, shot: 1, tick: 12, b: [[0, 760, 635, 4]] },
  { type: 'frame', seq: 5, shot: 1, tick: 18, b: [[0, 800, 635, 5]], last: true },
  stateMsg(6, [[0, 800, 635, 5]]), // the table at rest, sent before the playback ends
];

/**
 * Feed SHOT at wall time 0, then run the display loop at 60 Hz for `seconds`.
 * @param {number} [pace]
 * @param {number} [seconds]
 */
function playShot(pace = 1, seconds = 1) {
  /** @type {{name: string, time: number}[]} */
  const heard = [];
  const playback = new ShotPlayback({ delay: 0.1,
    onSound: (name) => heard.push({ name, time: playback.player.time }) });
  let state = initialState();
  for (const msg of SHOT) {
    const res = reduce(state, msg, 0);
    state = res.state;
    playback.setTable(state.table);
    for (const e of res.effects) playback.apply(e, 0);
  }
  const log = [];
  for (let k = 1; k <= seconds * 60; k++) {
    const now = k / 60;
    const balls = playback.update(1 / 60, now, pace);
    log.push({ now, busy: playback.busy, ids: [...balls.keys()],
      sinking: playback.sinking.list.map((s) => ({ ...s })), x0: balls.get(0)?.x });
  }
  return { playback, heard, log };
}

test('a shot plays back: frames counted, the pocket sound on time, the ball drops', () => {
  const { playback, heard, log } = playShot();
  assert.equal(playback.framesSeen, 3);
  assert.deepEqual(heard.map((h) => h.name), ['pocket']);
  assert.ok(heard[0].time >= 0.075 - 0.01, `pocket heard at ${heard[0].time}`);
  const gone = log.findIndex((l) => !l.ids.includes(3));
  assert.ok(gone > 0, 'ball 3 leaves the cloth');
  assert.ok(log[gone].busy, '... while the shot plays');
  const drop = log[gone].sinking.find((s) => s.id === 3);
  assert.ok(drop, 'and starts sinking the same frame');
  assert.deepEqual(drop.to, TABLE.pockets[3].center);
  assert.ok(Math.abs(drop.from[0] - 2.5) < 0.011 && Math.abs(drop.from[1] - 1.23) < 0.011);
  const over = log.findIndex((l, i) => i > gone && l.sinking.length === 0);
  assert.ok(Math.abs(log[over].now - log[gone].now - SINK_SECONDS) < 2 / 60 + 1e-9);
});

test('the table at rest waits for the playback to end, then is shown', () => {
  const { playback, log } = playShot();
  const done = log.findIndex((l) => !l.busy);
  assert.ok(done > 0);
  assert.ok(log.slice(0, done).every((l) => l.x0 === undefined || l.x0 <= 0.8 + 1e-9));
  assert.equal(playback.pendingRest, null);
  assert.equal(playback.player.playing, false, 'the rest state replaced the stream');
  assert.deepEqual([...playback.balls.keys()], [0]);
  assert.equal(playback.balls.get(0)?.x, 0.8);
});

test('pace 2 plays the same shot in about half the wall time', () => {
  const end = (/** @type {number} */ pace) => playShot(pace).log.findIndex((l) => !l.busy) / 60;
  const one = end(1);
  const two = end(2);
  assert.ok(one > 0.1 && two > 0, `${one} ${two}`);
  assert.ok(two < one * 0.75, `1x ${one} s, 2x ${two} s`);
});

test('reset puts a table down at once and forgets sounds and drops under way', () => {
  const { playback } = playShot(1, 0.1);
  playback.sounds.push({ sound: 'ball', speed: 1, t: 9 }, 0);
  playback.reset([{ id: 0, x: 1, y: 0.5, cel: 0 }, { id: 9, x: 2, y: 0.5, cel: 3 }]);
  assert.equal(playback.sounds.size, 0);
  assert.equal(playback.sinking.list.length, 0);
  assert.deepEqual([...playback.balls.keys()], [0, 9]);
  assert.equal(playback.busy, false);
  assert.equal(playback.done, true);
});
