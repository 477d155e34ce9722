import { test } from 'node:test';
import assert from 'node:assert/strict';
import { AimController, MAX_PULL } from '../js/input.js';
import { speedFromPower } from '../js/geometry.js';
import { DEFAULT_LIMITS, readLimits } from '../js/limits.js';
import { TABLE } from './fixtures.mjs';

/**
 * @param {Partial<import('../js/input.js').Situation>} [extra]
 * @returns {import('../js/input.js').Situation}
 */
const ctx = (extra = {}) => ({ table: TABLE, balls: [{ id: 0, x: 0.6, y: 0.6 },
  { id: 1, x: 1.9, y: 0.6 }], cue: [0.6, 0.6], myTurn: true, ballInHand: null,
  requiresCall: false, limits: DEFAULT_LIMITS, ...extra });

test('hover aims at the pointer; press, pull back and release shoots', () => {
  const a = new AimController();
  a.handle({ type: 'move', x: 1.6, y: 0.9, pointerType: 'mouse' }, ctx());
  const angle = Math.atan2(0.3, 1.0);
  assert.ok(Math.abs(a.angle - angle) < 1e-12);
  assert.deepEqual(a.handle({ type: 'down', x: 1.6, y: 0.9 }, ctx()), []);
  const back = MAX_PULL / 2;
  a.handle({ type: 'move', x: 1.6 - back * Math.cos(angle), y: 0.9 - back * Math.sin(angle) },
    ctx());
  assert.ok(Math.abs(a.power - 0.5) < 1e-9);
  const out = a.handle({ type: 'up', x: 1.6 - back * Math.cos(angle),
    y: 0.9 - back * Math.sin(angle) }, ctx());
  assert.equal(out.length, 1);
  assert.equal(out[0].type, 'shoot');
  assert.ok(Math.abs(out[0].angle - angle) < 1e-5);
  assert.ok(Math.abs(out[0].speed - speedFromPower(0.5, DEFAULT_LIMITS.max_speed)) < 1e-5);
  assert.deepEqual(out[0].tip, [0, 0]);
  assert.equal(a.mode, 'idle');
});

test('release without pulling back is a cancel; not my turn does nothing', () => {
  const a = new AimController();
  a.handle({ type: 'down', x: 1.6, y: 0.6 }, ctx());
  assert.deepEqual(a.handle({ type: 'up', x: 1.61, y: 0.6 }, ctx()), []);
  const b = new AimController();
  b.handle({ type: 'down', x: 1.6, y: 0.6 }, ctx({ myTurn: false }));
  b.handle({ type: 'move', x: 1.0, y: 0.6 }, ctx({ myTurn: false }));
  assert.deepEqual(b.handle({ type: 'up', x: 1.0, y: 0.6 }, ctx({ myTurn: false })), []);
});

test('ball in hand: drag the cue ball, the place is clamped behind the head string', () => {
  const a = new AimController();
  const c = ctx({ ballInHand: 'behind_head_string' });
  a.handle({ type: 'down', x: 0.61, y: 0.6 }, c);
  assert.equal(a.mode, 'placing');
  a.handle({ type: 'move', x: 1.5, y: 0.3 }, c);
  const out = a.handle({ type: 'up', x: 1.5, y: 0.3 }, c);
  assert.deepEqual(out, [{ type: 'place_cue', x: Math.round(TABLE.head_string * 1e6) / 1e6,
    y: 0.3 }]);
});

test('ball in hand on top of another ball is not sent', () => {
  const a = new AimController();
  const c = ctx({ ballInHand: 'anywhere' });
  a.handle({ type: 'down', x: 0.6, y: 0.6 }, c);
  a.handle({ type: 'move', x: 1.9, y: 0.61 }, c);
  assert.deepEqual(a.handle({ type: 'up', x: 1.9, y: 0.61 }, c), []);
});

test('calling the 8: a click on a pocket sends its index', () => {
  const a = new AimController();
  const out = a.handle({ type: 'down', x: 2.56, y: 1.29 }, ctx({ requiresCall: true }));
  assert.deepEqual(out, [{ type: 'call', pocket: 3 }]);
});

test('the spin tip goes out with the shot', () => {
  const a = new AimController();
  a.tip = [0.1, -0.2];
  a.handle({ type: 'down', x: 1.6, y: 0.6 }, ctx());
  const out = a.handle({ type: 'up', x: 1.2, y: 0.6 }, ctx());
  assert.deepEqual(out[0].tip, [0.1, -0.2]);
});

/**
 * Press at `x`, pull back to `x - pull` along +x from the cue ball and release.
 * @param {AimController} a
 * @param {import('../js/input.js').Situation} c
 * @param {number} pull metres
 */
function pullAndRelease(a, c, pull) {
  a.handle({ type: 'down', x: 1.6, y: 0.6 }, c);
  a.handle({ type: 'move', x: 1.6 - pull, y: 0.6 }, c);
  return a.handle({ type: 'up', x: 1.6 - pull, y: 0.6 }, c);
}

test("a full pull shoots at the server's max_speed, whatever it is", () => {
  const fast = pullAndRelease(new AimController(), ctx(), 2 * MAX_PULL);
  assert.equal(fast[0].speed, DEFAULT_LIMITS.max_speed);
  const limits = readLimits({ ...DEFAULT_LIMITS, max_speed: 7.5 });
  const slow = pullAndRelease(new AimController(), ctx({ limits }), 2 * MAX_PULL);
  assert.equal(slow[0].speed, 7.5);
  const half = pullAndRelease(new AimController(), ctx({ limits }), MAX_PULL / 2);
  assert.ok(Math.abs(half[0].speed - speedFromPower(0.5, 7.5)) < 1e-5);
});

test("the tip sent is clamped to the server's max_tip and never rounded outside it", () => {
  const a = new AimController();
  a.tip = [0.3, 0.4]; // on the edge of the default disc (0.5)
  const limits = readLimits({ max_tip: 0.25 });
  const out = pullAndRelease(a, ctx({ limits }), MAX_PULL);
  assert.ok(Math.hypot(out[0].tip[0], out[0].tip[1]) <= 0.25);
  assert.ok(Math.abs(out[0].tip[0] / out[0].tip[1] - 0.75) < 1e-4, 'same direction');
  const b = new AimController();
  b.tip = [0.5 * Math.cos(1), 0.5 * Math.sin(1)]; // exactly on the edge, irrational parts
  const edge = pullAndRelease(b, ctx(), MAX_PULL);
  assert.ok(Math.hypot(edge[0].tip[0], edge[0].tip[1]) <= 0.5);
});

test('a raised cue sends its elevation and the tip seen from behind at the bed', () => {
  const a = new AimController();
  a.tip = [0.5, 0];
  a.elevation = Math.PI / 3;
  const [shot] = pullAndRelease(a, ctx(), MAX_PULL);
  assert.equal(shot.elevation, 1.047197);
  assert.ok(Math.abs(shot.tip[0] - 0.4995) < 1e-6);
  // The tip's point seen along a 60 degree cue lies 0.75 R up the ball seen level.
  assert.ok(Math.abs(shot.tip[1] - 0.75) < 2e-3);
  const level = new AimController();
  level.tip = [0.5, 0];
  const [flat] = pullAndRelease(level, ctx(), MAX_PULL);
  assert.equal('elevation' in flat, false, 'a level shot is the message it always was');
  assert.deepEqual(flat.tip, [0.5, 0]);
});
