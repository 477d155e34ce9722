import { test } from 'node:test';
import assert from 'node:assert/strict';
import { AimController } from '../js/input.js';
import { objectPath, placeCue, placementArea } from '../js/geometry.js';
import { DEFAULT_LIMITS } from '../js/limits.js';
import { TABLE } from './fixtures.mjs';

const R = TABLE.ball_radius;
/**
 * @param {Partial<import('../js/input.js').Situation>} [extra]
 * @returns {import('../js/input.js').Situation}
 */
const ctx = (extra = {}) => ({ table: TABLE, balls: [{ id: 0, x: 0.6, y: 0.6 },
  { id: 1, x: 1.9, y: 0.6 }], cue: [0.6, 0.6], myTurn: true, ballInHand: null,
  requiresCall: false, limits: DEFAULT_LIMITS, ...extra });

test('a press released without pulling back is a cancelled shot, and says so', () => {
  const a = new AimController();
  a.handle({ type: 'down', x: 1.6, y: 0.6 }, ctx());
  assert.equal(a.tooShort, true);
  assert.deepEqual(a.handle({ type: 'up', x: 1.6, y: 0.6 }, ctx()), []);
  assert.equal(a.feedback.seq, 1);
  assert.equal(a.feedback.kind, 'cancelled');
  assert.match(a.feedback.text, /pull back/);
  // Escape while pulling cancels too; a shot that goes does not add a note.
  a.handle({ type: 'down', x: 1.6, y: 0.6 }, ctx());
  a.handle({ type: 'cancel' }, ctx());
  assert.equal(a.feedback.seq, 2);
  a.handle({ type: 'down', x: 1.6, y: 0.6 }, ctx());
  a.handle({ type: 'move', x: 1.3, y: 0.6 }, ctx());
  assert.equal(a.tooShort, false);
  assert.equal(a.handle({ type: 'up', x: 1.3, y: 0.6 }, ctx())[0].type, 'shoot');
  assert.equal(a.feedback.seq, 2);
});

test('dropping the cue ball on another ball is refused with the reason', () => {
  const a = new AimController();
  const c = ctx({ ballInHand: 'anywhere' });
  a.handle({ type: 'down', x: 0.6, y: 0.6 }, c);
  a.handle({ type: 'move', x: 1.9 + R, y: 0.6 }, c);
  assert.deepEqual(a.handle({ type: 'up', x: 1.9 + R, y: 0.6 }, c), []);
  assert.equal(a.feedback.kind, 'refused');
  assert.match(a.feedback.text, /another ball/);
});

test('a cue ball held past the head string stays on it and is marked clamped', () => {
  const kitchen = placementArea(TABLE, 'behind_head_string');
  assert.ok(kitchen);
  assert.equal(placeCue(TABLE, kitchen, [], 1.5, 0.6).clamped, true);
  assert.equal(placeCue(TABLE, kitchen, [], 0.3, 0.6).clamped, false);
});

test('fine aim turns the cue by the step and keeps the angle in (-pi, pi]', () => {
  const a = new AimController();
  a.angle = Math.PI - 0.001;
  a.nudge(0.002);
  assert.ok(Math.abs(a.angle - (-Math.PI + 0.001)) < 1e-12);
  assert.equal(a.dirty, true);
});

test("the object ball's path ends at the cushion, a ball or the pocket it drops in", () => {
  // Straight across the table: the centre stops one radius short of the far cushion.
  const across = objectPath(TABLE, [], [1.0, 0.6], [0, 1]);
  assert.equal(across.kind, 'cushion');
  assert.ok(Math.abs(across.end[1] - (TABLE.width - R)) < 1e-12);
  // Another ball on the way: it stops touching it.
  const blocked = objectPath(TABLE, [{ id: 3, x: 1.0, y: 1.0 }], [1.0, 0.6], [0, 1]);
  assert.equal(blocked.kind, 'ball');
  assert.ok(Math.abs(blocked.end[1] - (1.0 - 2 * R)) < 1e-12);
  // Into the side pocket's mouth: it ends where it drops, never past the rail line.
  const side = objectPath(TABLE, [], [TABLE.length / 2, 0.6], [0, -1]);
  assert.equal(side.kind, 'pocket');
  assert.ok(side.end[1] > -0.1 && side.end[1] < 0.05);
  // To the corner: the pocket too, the line never leaves the table's box.
  const corner = objectPath(TABLE, [], [0.5, 0.5], [-Math.SQRT1_2, -Math.SQRT1_2]);
  assert.equal(corner.kind, 'pocket');
  assert.ok(corner.end[0] > -0.05 && corner.end[1] > -0.05);
});
