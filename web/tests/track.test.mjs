import { test } from 'node:test';
import assert from 'node:assert/strict';
import {
  decodeMotion, trackAt, motionAt, celOf, base64Bytes, soundHeard,
} from '../js/track.js';
import { encodeMotion } from './motion.mjs';

const R = 0.028575;
const TURN = 2 * Math.PI;

/** A cue ball rolling +x into a still ball 1 at t = 0.2, which rolls on and drops. */
const SHOT = {
  seq: 42, shot: 7, duration: 1.0,
  tracks: [
    { id: 0, t: [0, 0.2, 0.5], x: [0.5, 0.9, 0.95], y: [0.6, 0.6, 0.6],
      phase: [0, 0.4 / R, 0.45 / R] },
    { id: 1, pocket: 2, t: [0, 0.2, 0.7], x: [0.9571, 0.9571, 2.5], y: [0.6, 0.6, 0.6],
      phase: [1, 1, 1 + 1.5429 / R] },
    { id: 9, t: [0], x: [2.0], y: [1.0], phase: [TURN * 0.25] },
  ],
  sounds: [
    { t: 0, kind: 'strike', ids: [0], speed: 4 },
    { t: 0.2, kind: 'ball', ids: [0, 1], speed: 2.5 },
    { t: 0.7, kind: 'pocket', ids: [1], speed: 3.1, target: 2 },
  ],
};

test('the documented bytes decode to the header, the knots and the sounds', () => {
  const m = decodeMotion(encodeMotion(SHOT));
  assert.equal(m.type, 'motion');
  assert.equal(m.seq, 42);
  assert.equal(m.shot, 7);
  assert.equal(m.duration, 1.0);
  assert.deepEqual(m.tracks.map((t) => [t.id, t.pocket, t.t.length]), [[0, null, 3], [1, 2, 3],
    [9, null, 1]]);
  const cue = m.tracks[0];
  assert.deepEqual([...cue.t], [0, 0.2, 0.5]);
  assert.ok(Math.abs(cue.x[1] - 0.9) < 1e-9 && Math.abs(cue.y[2] - 0.6) < 1e-9);
  assert.ok(Math.abs(cue.phase[1] - 0.4 / R) < TURN / 4096);
  assert.deepEqual(m.sounds.map((s) => [s.kind, s.ids, s.target]),
    [['strike', [0], -1], ['ball', [0, 1], -1], ['pocket', [1], 2]]);
  assert.equal(m.sounds[2].t, 0.7);
  assert.equal(m.sounds[1].speed, 2.5);
});

test('negative coordinates and long deltas survive (pocket centres lie off the bed)', () => {
  const m = decodeMotion(encodeMotion({ shot: 1, duration: 3, tracks: [
    { id: 3, pocket: 0, t: [0, 2.9], x: [2.5, -0.0212], y: [1.2, -0.0212], phase: [0, -40] }],
  }));
  const tr = m.tracks[0];
  assert.ok(Math.abs(tr.x[1] + 0.0212) < 1e-9 && Math.abs(tr.y[1] + 0.0212) < 1e-9);
  assert.ok(Math.abs(tr.phase[1] + 40) < TURN / 4096);
  assert.equal(tr.t[1], 2.9);
});

test('between knots a ball moves in a straight line at constant speed', () => {
  const m = decodeMotion(encodeMotion(SHOT));
  const cue = m.tracks[0];
  const at = trackAt(cue, 0.1);
  assert.ok(at);
  assert.ok(Math.abs(at.x - 0.7) < 1e-9 && Math.abs(at.y - 0.6) < 1e-9);
  assert.ok(Math.abs(at.speed - 2.0) < 1e-9);
  assert.equal(at.heading, 0);
  // At the contact's exact time the two balls touch: centres 2R apart.
  const [a, b] = [trackAt(cue, 0.2), trackAt(m.tracks[1], 0.2)];
  assert.ok(a && b && Math.abs(Math.hypot(b.x - a.x, b.y - a.y) - 2 * R) < 1e-4);
});

test('a ball rests at its last knot and its sprite stops turning there', () => {
  const m = decodeMotion(encodeMotion(SHOT));
  const cue = m.tracks[0];
  const late = [0.5, 0.6, 0.99].map((t) => trackAt(cue, t));
  for (const p of late) {
    assert.ok(p);
    assert.equal(p.x, late[0]?.x);
    assert.equal(p.cel, late[0]?.cel);
    assert.equal(p.speed, 0);
  }
  const still = trackAt(m.tracks[2], 0.5);
  assert.ok(still && still.x === 2 && still.cel === 4 && Number.isNaN(still.heading));
});

test('the cel follows the roll: one turn of 2πR of travel is 16 cels', () => {
  assert.equal(celOf(0, 16), 0);
  assert.equal(celOf(TURN / 16 + 1e-9, 16), 1);
  assert.equal(celOf(-1e-9, 16), 15);
  assert.equal(celOf(TURN * 3.5, 16), 8);
  const m = decodeMotion(encodeMotion(SHOT));
  const cels = [];
  for (let t = 0; t <= 0.2; t += 0.001) cels.push(trackAt(m.tracks[0], t)?.cel);
  // 0.4 m rolled is 0.4 / (2πR) = 2.23 turns: every cel comes round, in order.
  assert.ok(new Set(cels).size === 16);
});

test('a pocketed ball is on the table up to its drop, then gone', () => {
  const m = decodeMotion(encodeMotion(SHOT));
  const ids = (/** @type {number} */ t) => motionAt(m, t).map((p) => p.id);
  assert.deepEqual(ids(0.7), [0, 1, 9]);
  const drop = motionAt(m, 0.7).find((p) => p.id === 1);
  assert.ok(drop && Math.abs(drop.x - 2.5) < 1e-9, 'drawn where it really drops');
  assert.deepEqual(ids(0.7001), [0, 9]);
});

test('before its first knot a track holds; a replay line carries the bytes in base64', () => {
  const bytes = encodeMotion(SHOT);
  const text = Buffer.from(bytes).toString('base64');
  const m = decodeMotion(base64Bytes(text));
  assert.equal(trackAt(m.tracks[0], -1)?.x, 0.5);
  assert.deepEqual(m, decodeMotion(bytes));
});

test('a truncated, foreign or padded message is refused', () => {
  const bytes = encodeMotion(SHOT);
  assert.throws(() => decodeMotion(bytes.slice(0, bytes.length - 3)));
  assert.throws(() => decodeMotion(Uint8Array.from([2, ...bytes.slice(1)])));
  assert.throws(() => decodeMotion(Uint8Array.from([...bytes, 0])));
});

/** docs/protocol.md, `motion` version 2: the cue ball hops 45.0 mm over 0.1 s. */
const HOP_HEX = `01 02 09 00 00 00 04 00 00 00 a0 86 01 00 01 01 00
00 ff 03 00 00 ce 18 ce 18 00 00 00 00 d0 86 03 94 0a 00 00 84 07 d0 86 03 94 0a 00 00 83 07
00 00 00 ff ff b8 0b`;

/** @param {string} text */
const hexBytes = (text) => Uint8Array.from(text.trim().split(/\s+/), (h) => parseInt(h, 16));

test('version 2 (a ball flies) decodes each knot\'s height, and the pose has z', () => {
  const m = decodeMotion(hexBytes(HOP_HEX));
  assert.equal(m.seq, 9);
  assert.equal(m.shot, 4);
  const [cue] = m.tracks;
  assert.deepEqual([...cue.z], [0, 0.045, 0]);
  assert.deepEqual([...cue.x], [0.635, 0.7, 0.765]);
  assert.equal(cue.offTable, false);
  assert.ok(Math.abs((trackAt(cue, 0.025)?.z ?? NaN) - 0.0225) < 1e-12);
  assert.equal(trackAt(cue, 0.1)?.z, 0);
  assert.deepEqual(m.sounds, [{ t: 0, kind: 'strike', ids: [0], speed: 3, target: -1 }]);
});

test('version 1 still decodes, every height 0', () => {
  const m = decodeMotion(encodeMotion(SHOT));
  assert.equal(trackAt(m.tracks[0], 0.1)?.z, 0);
  assert.ok(m.tracks.every((t) => t.offTable === false));
});

test('version 2: pocket 254 is a ball that flies off the table at its last knot', () => {
  const bytes = hexBytes(HOP_HEX);
  bytes[18] = 254;
  const [cue] = decodeMotion(bytes).tracks;
  assert.equal(cue.offTable, true);
  assert.equal(cue.pocket, null);
  assert.notEqual(trackAt(cue, 0.1), null);
  assert.equal(trackAt(cue, 0.2), null);
});

test("a strike that sends its ball off the slate is heard as the jump's click", () => {
  const hop = decodeMotion(hexBytes(HOP_HEX));
  const strike = hop.sounds[0];
  const land = { t: 0.1, kind: 'land', ids: [0], speed: 0.5, target: -1 };
  const jumped = { ...hop, sounds: [strike, land] };
  assert.equal(soundHeard(jumped, strike), 'jump');
  assert.equal(soundHeard(jumped, land), 'land');
  // Without a landing (a level shot: every height 0) the strike is a strike.
  assert.equal(soundHeard(hop, strike), 'strike');
  const flat = decodeMotion(encodeMotion(SHOT));
  assert.equal(soundHeard(flat, flat.sounds[0]), 'strike');
});
