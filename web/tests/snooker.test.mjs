import { test } from 'node:test';
import assert from 'node:assert/strict';
import { frameLines, nominationAt } from '../js/screens/table/snooker.js';
import { placementArea, placeCue } from '../js/geometry.js';
import { ballColor, ballIds, isStripe, snookerBallName } from '../js/balls.js';
import { surfaceAt } from '../js/sprites.js';

/** @type {import('../js/geometry.js').Table} */
const SNOOKER = {
  length: 3.569, width: 1.778, ball_radius: 0.02625, head_string: 0.737, style: 'snooker',
  cushions: [], pockets: [],
  arcs: [{ center: [0.737, 0.889], radius: 0.292, start_deg: 90, end_deg: 270 }],
};

test('the scoreboard says the points, the snookers required, the break and the ball on', () => {
  const lines = frameLines({
    points: [40, 3], current_break: 12, highest_break: [12, 3], on: 'colour', nominated: 20,
    free_ball: false, remaining: 51, snookers_required: [0, 0],
  }, ['Ana', 'Ben'], [1, 0], 0);
  assert.deepEqual(lines, [
    'Ana (1): 40', 'Ben (0): 3', 'Break 12 (Ana) · on a colour · nominated the pink',
    'Remaining 51',
  ]);
  const behind = frameLines({
    points: [60, 10], current_break: 0, highest_break: [0, 0], on: 'pink', nominated: null,
    free_ball: true, remaining: 13, snookers_required: [0, 10],
  }, ['Ana', 'Ben'], undefined, 1);
  assert.equal(behind[1], 'Ben: 10 · needs 10 snookers');
  assert.match(behind[2], /on the pink · free ball/);
});

test('a tap on a ball that may be nominated nominates it', () => {
  const balls = [{ id: 0, x: 1, y: 1 }, { id: 20, x: 2.6, y: 0.9 }];
  assert.equal(nominationAt(balls, [20], 0.02625, 2.61, 0.9), 20);
  assert.equal(nominationAt(balls, [20], 0.02625, 1, 1), null);
  assert.equal(nominationAt(balls, [21], 0.02625, 2.6, 0.9), null);
});

test('ball in hand in the D keeps the dragged cue ball in the D', () => {
  const area = placementArea(SNOOKER, 'in_d');
  assert.ok(area?.disc);
  const inside = placeCue(SNOOKER, area, [], 0.6, 0.9);
  assert.deepEqual([inside.x, inside.y, inside.clamped], [0.6, 0.9, false]);
  const out = placeCue(SNOOKER, area, [], 1.2, 0.889 + 0.5);
  assert.ok(out.clamped && out.x <= 0.737);
  assert.ok(Math.hypot(out.x - 0.737, out.y - 0.889) <= 0.292);
});

test('snooker balls are plain reds and colours, without numbers or stripes', () => {
  assert.equal(ballIds('snooker').length, 22);
  assert.equal(ballColor(20, 'snooker'), '#f08cb0');
  assert.equal(ballColor(7, 'snooker'), ballColor(1, 'snooker')); // every red alike
  assert.equal(isStripe(9, 'snooker'), false);
  assert.equal(surfaceAt(9, [0, 0, 1], 'snooker').decal, null);
  assert.equal(snookerBallName(21), 'the black');
  assert.equal(snookerBallName(3), 'a red');
});
