import { test } from 'node:test';
import assert from 'node:assert/strict';
import { caromLines, CushionCounter, strikerBall } from '../js/screens/table/carom.js';
import { ballColor, ballIds, isStripe } from '../js/balls.js';

const CAROM = { length: 2.84, width: 1.42, ball_radius: 0.03075 };

test('the scoreboard says points, innings, average and high run for each player', () => {
  const lines = caromLines({
    points: [7, 3], innings: [4, 4], average: [1.75, 0.75], high_run: [4, 2], run: 2,
    race_to: 15, last_inning: false, cue_balls: [0, 1], opening: false,
  }, ['Ana', 'Ben'], 0);
  assert.deepEqual(lines, [
    'Ana (white): 7 · innings 4 · average 1.750 · high run 4',
    'Ben (yellow): 3 · innings 4 · average 0.750 · high run 2',
    'Race to 15 · run 2 (Ana)',
  ]);
});

test('cushions are counted as the ball comes to a rail, once each time', () => {
  const counter = new CushionCounter();
  counter.reset();
  for (const [x, y] of [[1.0, 0.7], [1.5, 0.3], [2.0, 0.0315], [2.3, 0.2], [2.808, 0.5],
    [2.808, 0.52], [2.0, 1.0], [1.0, 1.39]]) counter.update(CAROM, x, y);
  assert.equal(counter.count, 3);
  counter.reset();
  assert.equal(counter.count, 0);
});

test('the striker strikes the cue ball of the seat at the table', () => {
  const state = /** @type {any} */ ({ match: { turn: 1, carom: { cue_balls: [0, 1] } } });
  assert.equal(strikerBall(state), 1);
  assert.equal(strikerBall(/** @type {any} */ ({ match: { turn: 1 } })), 0);
});

test('three balls painted white, yellow and red, no stripes', () => {
  assert.deepEqual(ballIds('carom'), [0, 1, 2]);
  assert.equal(ballColor(2, 'carom'), '#c8141b');
  assert.equal(ballColor(1, 'carom'), '#f4c20d');
  assert.equal(isStripe(1, 'carom'), false);
});
