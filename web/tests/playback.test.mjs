import { test } from 'node:test';
import assert from 'node:assert/strict';
import { ShotPlayback, shownTrack, sinkPose, SINK_SECONDS } from '../js/playback.js';
import { decodeMotion, trackAt } from '../js/track.js';
import { initialState, reduce } from '../js/state.js';
import { encodeMotion } from './motion.mjs';
import { TABLE } from './fixtures.mjs';

const R = 0.028575;

/**
 * A break-like shot: the cue ball hits ball 1 at 0.2 s and stops; ball 1 rolls into the
 * bottom-right pocket (index 2) at 0.7 s; ball 9 never moves. Sounds at their times.
 */
const SHOT = {
  shot: 7, duration: 1.0,
  tracks: [
    { id: 0, t: [0, 0.2, 0.5], x: [0.5, 0.9, 0.95], y: [0.6, 0.6, 0.6],
      phase: [0, 0.4 / R, 0.45 / R] },
    { id: 1, pocket: 2, t: [0, 0.2, 0.7], x: [0.9571, 0.9571, 2.52], y: [0.6, 0.6, 0.01],
      phase: [1, 1, 1 + 1.6 / R] },
    { id: 9, t: [0], x: [2.0], y: [1.0], phase: [0] },
  ],
  sounds: [
    { t: 0, kind: 'strike', ids: [0], speed: 4 },
    { t: 0.2, kind: 'ball', ids: [0, 1], speed: 2.5 },
    { t: 0.7, kind: 'pocket', ids: [1], speed: 3.1, target: 2 },
  ],
};
const motion = () => decodeMotion(encodeMotion(SHOT));

/**
 * A playback of SHOT from `t0`, recording its sounds as [kind, playback time].
 * @param {number} [t0]
 */
function playing(t0 = 0) {
  /** @type {[string, number][]} */
  const heard = [];
  const p = new ShotPlayback({ onSound: (kind) => heard.push([kind, p.time]) });
  p.setTable(TABLE);
  p.apply({ kind: 'motion', motion: motion(), t0 }, 100);
  return { p, heard };
}

/**
 * Run the playback at 60 fps from wall time `from` for `seconds`.
 * @param {ShotPlayback} p
 * @param {number} seconds
 * @param {number} [from]
 * @param {number} [pace]
 */
function run(p, seconds, from = 100, pace = 1) {
  let now = from;
  for (let i = 0; i < Math.round(seconds * 60); i++) {
    now += 1 / 60;
    p.update(1 / 60, now, pace);
  }
  return now;
}

test('the balls drawn are the tracks at the playback time, on the client`s clock', () => {
  const { p } = playing();
  const m = motion();
  run(p, 0.1);
  const cue = p.balls.get(0);
  const exact = trackAt(m.tracks[0], p.time);
  assert.ok(cue && exact);
  assert.ok(Math.abs(p.time - 0.1) < 1e-9);
  assert.ok(Math.abs(cue.x - exact.x) < 1e-12 && cue.cel === exact.cel);
  assert.ok(p.busy);
});

test('every sound plays once, in order, when the playback reaches its time', () => {
  const { p, heard } = playing();
  assert.deepEqual(heard, [['strike', 0]], 'the strike at once');
  run(p, 1.2);
  assert.deepEqual(heard.map(([k]) => k), ['strike', 'ball', 'pocket']);
  for (const [kind, at] of heard.slice(1)) {
    const due = kind === 'ball' ? 0.2 : 0.7;
    assert.ok(at >= due - 1e-9 && at < due + 1 / 60, `${kind} at ${at}`);
  }
  assert.ok(p.done && !p.busy);
});

test('a late joiner starts where the shot is: no earlier sound, no earlier drop', () => {
  const { p, heard } = playing(0.8);
  assert.ok(Math.abs(p.time - 0.8) < 1e-9);
  assert.equal(p.balls.has(1), false, 'ball 1 dropped before we came');
  run(p, 0.5);
  assert.deepEqual(heard, []);
  assert.deepEqual(p.sinking.list, []);
  assert.equal(p.balls.get(0)?.x, 0.95);
});

test('a pocketed ball slides from where it dropped into its pocket, from that instant', () => {
  const { p } = playing();
  const now = run(p, 0.71);
  assert.equal(p.balls.has(1), false);
  const [sink] = p.sinking.list;
  assert.ok(sink);
  assert.deepEqual(sink.from, [2.52, 0.01]);
  assert.deepEqual(sink.to, TABLE.pockets[2].center);
  // It started at the drop's own time, not at the display frame that noticed it.
  const dropAt = now - (p.time - 0.7);
  assert.ok(Math.abs(sink.start - dropAt) < 1e-9);
  assert.ok(sink.duration > 0 && sink.duration <= SINK_SECONDS);
  const pose = sinkPose(sink, sink.start);
  assert.deepEqual([pose.x, pose.y, pose.f], [2.52, 0.01, 0]);
  run(p, 0.3, now);
  assert.deepEqual(p.sinking.list, [], 'the drop ends');
});

test('the table at rest waits for the playback to end, then is shown', () => {
  const { p } = playing();
  run(p, 0.3);
  const rest = [{ id: 0, x: 0.95, y: 0.6, cel: 3 }, { id: 9, x: 2, y: 1, cel: 0 }];
  p.apply({ kind: 'rest', balls: rest }, 100.3);
  assert.ok(p.busy && p.balls.has(1), 'still rolling');
  run(p, 1, 100.3);
  assert.deepEqual([...p.balls.keys()], [0, 9]);
  assert.equal(p.balls.get(0)?.cel, 3);
});

test('pace 2 plays the same shot in half the wall time', () => {
  const { p } = playing();
  run(p, 0.5, 100, 2);
  assert.ok(p.done);
});

test('window.pool.track: the last shot shown, at any instant, until the next starts', () => {
  const { p } = playing();
  run(p, 1.5);
  const at = shownTrack(0.2);
  assert.deepEqual(at.map((b) => b.id), [0, 1, 9]);
  const [cue, one] = at;
  assert.ok(Math.abs(Math.hypot(one.x - cue.x, one.y - cue.y) - 2 * R) < 1e-4, 'touching');
  assert.deepEqual(shownTrack(0.9).map((b) => b.id), [0, 9]);
  p.apply({ kind: 'rest', balls: [{ id: 0, x: 1, y: 1 }] }, 200);
  assert.equal(shownTrack(0.2).length, 3, 'still the last shot shown');
});

test('the reducer and the playback together: a spectator joining mid-shot is in sync', () => {
  let s = initialState();
  const p = new ShotPlayback();
  p.setTable(TABLE);
  const feed = (/** @type {any} */ msg, /** @type {number} */ now) => {
    const r = reduce(s, msg, now);
    s = r.state;
    for (const e of r.effects) p.apply(e, now);
  };
  feed({ type: 'welcome', seq: 3, tick_hz: 120, role: 'spectator' }, 50);
  feed({ type: 'state', seq: 3, phase: 'rolling', table: TABLE, balls: [[0, 900, 600, 0]],
    shot: { id: 7, seat: 0, tick: 36, ticks: 120 }, clock: null, grace: [], match: null }, 50);
  assert.equal(p.balls.get(0)?.x, 0.9, 'the state`s balls until the motion comes');
  feed({ ...motion(), seq: 2 }, 50.05);
  assert.ok(Math.abs(p.time - 0.35) < 1e-9, '36 ticks in, plus the 50 ms since');
  assert.equal(s.phase, 'rolling');
  assert.equal(p.framesSeen, 1);
});
