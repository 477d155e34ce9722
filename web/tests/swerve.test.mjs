import { test } from 'node:test';
import assert from 'node:assert/strict';
import { cueBallPath, curvedGuide, offsetAt } from '../js/swerve.js';
import { squirt } from '../js/geometry.js';

import { TABLE } from './fixtures.mjs';

const R = TABLE.ball_radius;
const MASS_RATIO = 30; // the server's cue_mass_ratio
const MM = 0.001;
const rad = (/** @type {number} */ deg) => (deg * Math.PI) / 180;

/**
 * A stroke at angle 0 with `side` of the radius along the cue, the tip named as the server
 * names it (seen level: `tip_seen_level((side, 0), elevation)`).
 * @param {number} degrees
 * @param {number} speed
 * @param {number} side
 */
function stroke(degrees, speed, side) {
  const e = rad(degrees);
  return { angle: 0, speed, tip: [side, Math.sin(e) * Math.sqrt(1 - side * side)], elevation: e };
}

// The engine's offsets from the aim line (m, + left) 0.5 m and 1 m down it, for the cue
// ball alone on the 9 ft table at (0.5, W/2), 0.4995 R of right side along the cue:
//   ShotInMotion(Table.pool("9ft"), BallSet.place({0: (0.5, W/2)}),
//                Shot(0.0, speed, tip_seen_level((0.4995, 0.0), e), e)).run(trace=TRACE)
// read between the trace's samples (a tick apart, so within ~1 mm of the true curve).
const ENGINE = [
  { degrees: 60, speed: 2, at: [-0.17649, -0.58067] }, // massé
  { degrees: 30, speed: 3, at: [0.01111, -0.02928] }, // squirts left, then swerves right
  { degrees: 15, speed: 2, at: [-0.00453, -0.05102] }, // swerve
];

test("a raised cue's path curves as the engine moves the ball, within 2 mm over 1 m", () => {
  for (const { degrees, speed, at } of ENGINE) {
    const path = cueBallPath([0.5, TABLE.width / 2], stroke(degrees, speed, 0.4995), R, MASS_RATIO);
    const [half, metre] = [offsetAt(path, 0, 0.5), offsetAt(path, 0, 1)];
    assert.ok(Math.abs(half - at[0]) <= 2 * MM, `${degrees}°: ${half} at 0.5 m, engine ${at[0]}`);
    assert.ok(Math.abs(metre - at[1]) <= 2 * MM, `${degrees}°: ${metre} at 1 m, engine ${at[1]}`);
  }
});

test('left english curves left as right english curves right', () => {
  const right = cueBallPath([0.5, 0.6], stroke(60, 2, 0.4995), R, MASS_RATIO);
  const left = cueBallPath([0.5, 0.6], stroke(60, 2, -0.4995), R, MASS_RATIO);
  assert.ok(offsetAt(right, 0, 1) < -0.5);
  assert.ok(Math.abs(offsetAt(left, 0, 1) + offsetAt(right, 0, 1)) < 1e-9);
});

test('a level stroke goes straight along the squirted line', () => {
  const level = { angle: 0, speed: 2, tip: [0.3, 0.2], elevation: 0 };
  const path = cueBallPath([0.5, 0.6], level, R, MASS_RATIO);
  const expected = Math.tan(squirt(0.3, MASS_RATIO));
  assert.ok(Math.abs(offsetAt(path, 0, 1) - expected) < 1e-9);
});

test('a jump guide passes over the ball in its way and meets the one behind', () => {
  const y = TABLE.width / 2;
  const balls = [{ id: 0, x: 0.5, y }, { id: 1, x: 0.75, y }, { id: 2, x: 1.5, y }];
  const jump = { angle: 0, speed: 4, tip: [0, Math.sin(rad(45))], elevation: rad(45) };
  const over = curvedGuide(TABLE, balls, [0.5, y], jump, MASS_RATIO);
  assert.equal(over.guide.hitId, 2);
  const level = curvedGuide(TABLE, balls, [0.5, y], { ...jump, tip: [0, 0], elevation: 0 },
    MASS_RATIO);
  assert.equal(level.guide.hitId, 1);
});
