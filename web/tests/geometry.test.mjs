import { test } from 'node:test';
import assert from 'node:assert/strict';
import {
  tipSeenLevel, tipAlongCue,
  makeView, castGuide, rayCircle, rayCushion, placementArea, placeCue, pocketAt, pullPower,
  speedFromPower, clampTip, squirt, MIN_SPEED,
} from '../js/geometry.js';

import { TABLE } from './fixtures.mjs';

const R = TABLE.ball_radius;
const L = TABLE.length;
const W = TABLE.width;
/** @type {(x: number, y: number, eps?: number) => void} */
const close = (x, y, eps = 1e-9) => assert.ok(Math.abs(x - y) <= eps, `${x} != ${y}`);

test('the view maps table metres to pixels and back, y up on the table, down on screen', () => {
  const v = makeView(TABLE, 1000, 600);
  const [x0, y0] = v.toScreen(0, 0);
  const [x1, y1] = v.toScreen(L, W);
  assert.ok(x1 > x0 && y1 < y0, 'x grows right, table y grows up the screen');
  close(x1 - x0, L * v.scale);
  const [bx, by] = v.toTable(...v.toScreen(1.234, 0.567));
  close(bx, 1.234, 1e-12);
  close(by, 0.567, 1e-12);
  // The whole table with rails fits, centred.
  assert.ok(x0 > 0 && x1 < 1000 && y1 > 0 && y0 < 600);
  close((x0 + x1) / 2, 500, 1e-9);
});

test('rayCircle finds the first touch and ignores circles behind', () => {
  close(rayCircle(0, 0, 1, 0, 5, 0, 1), 4);
  assert.equal(rayCircle(0, 0, -1, 0, 5, 0, 1), Infinity);
  assert.equal(rayCircle(0, 0, 1, 0, 5, 3, 1), Infinity);
});

test('a straight shot at a ball: ghost ball two radii short, object ball straight on', () => {
  const g = castGuide(TABLE, [{ id: 0, x: 0.5, y: 0.6 }, { id: 5, x: 1.5, y: 0.6 }],
    [0.5, 0.6], 0);
  assert.equal(g.kind, 'ball');
  assert.equal(g.hitId, 5);
  close(g.contact[0], 1.5 - 2 * R, 1e-12);
  close(g.contact[1], 0.6, 1e-12);
  assert.ok(g.objectDir);
  close(g.objectDir[0], 1, 1e-12);
  assert.equal(g.cueDir, null, 'a full hit stops the cue ball dead (stun)');
});

test('a cut: object ball along the line of centres, cue ball along the tangent (90 degrees)', () => {
  const ball = { id: 3, x: 1.5, y: 0.6 + R }; // half-ball hit from the left
  const g = castGuide(TABLE, [ball], [0.5, 0.6], 0);
  assert.equal(g.kind, 'ball');
  assert.ok(g.objectDir && g.cueDir);
  const dx = ball.x - g.contact[0];
  const dy = ball.y - g.contact[1];
  close(Math.hypot(dx, dy), 2 * R, 1e-12);
  close(g.objectDir[0], dx / (2 * R), 1e-12);
  const dot = g.objectDir[0] * g.cueDir[0] + g.objectDir[1] * g.cueDir[1];
  close(dot, 0, 1e-12);
  assert.ok(g.objectDir[1] > 0 && g.cueDir[1] < 0, 'object goes up, cue ball down');
});

test('the nearest ball wins and balls off the line are ignored', () => {
  const balls = [{ id: 9, x: 2.0, y: 0.6 }, { id: 4, x: 1.0, y: 0.6 }, { id: 2, x: 0.8, y: 0.9 }];
  assert.equal(castGuide(TABLE, balls, [0.5, 0.6], 0).hitId, 4);
});

test('towards a cushion: the ghost ball touches it and the cue ball mirrors', () => {
  const angle = Math.PI / 4;
  const g = castGuide(TABLE, [], [0.5, 0.3], angle);
  assert.equal(g.kind, 'cushion');
  assert.ok(g.cueDir);
  close(g.contact[1], W - R, 1e-12); // top cushion, one radius short
  close(g.cueDir[0], Math.cos(angle), 1e-12);
  close(g.cueDir[1], -Math.sin(angle), 1e-12);
});

test('rayCushion misses when the foot falls in a pocket mouth', () => {
  const c = TABLE.cushions[0];
  assert.equal(rayCushion(L / 2, 0.5, 0, -1, c, R), Infinity); // into the side pocket
  close(rayCushion(0.6, 0.5, 0, -1, c, R), 0.5 - R, 1e-12);
});

test('straight into a corner pocket: no cushion, the guide runs past the mouth', () => {
  const g = castGuide(TABLE, [], [0.5, 0.5], Math.atan2(-0.5, -0.5));
  assert.equal(g.kind, 'none');
  assert.ok(g.contact[0] < 0 && g.contact[1] < 0);
});

test('ball in hand: the kitchen or the whole bed, and overlap is reported', () => {
  assert.equal(placementArea(TABLE, null), null);
  const kitchen = placementArea(TABLE, 'behind_head_string');
  assert.ok(kitchen);
  close(kitchen.x1, L / 4);
  const anywhere = placementArea(TABLE, 'anywhere');
  assert.ok(anywhere);
  close(anywhere.x1, L - R);
  const p = placeCue(TABLE, kitchen, [], 2.0, 5);
  close(p.x, L / 4);
  close(p.y, W - R);
  assert.equal(p.free, true);
  const q = placeCue(TABLE, anywhere, [{ id: 1, x: 1, y: 0.6 }], 1 + R, 0.6);
  assert.equal(q.free, false);
});

test('a click on a pocket names its index', () => {
  assert.equal(pocketAt(TABLE, L / 2, -0.03), 1);
  assert.equal(pocketAt(TABLE, L + 0.01, W + 0.01), 3);
  assert.equal(pocketAt(TABLE, 1, 0.6), -1);
});

test('pulling back sets power; pushing forward does not', () => {
  close(pullPower([1, 0.5], [0.8, 0.5], 0, 0.4), 0.5, 1e-12);
  assert.equal(pullPower([1, 0.5], [1.3, 0.5], 0, 0.4), 0);
  assert.equal(pullPower([1, 0.5], [0, 0.5], 0, 0.4), 1);
});

test("power maps into the server's speed range, monotonically", () => {
  let prev = 0;
  for (let p = 0; p <= 1.0001; p += 0.05) {
    const v = speedFromPower(p, 12);
    assert.ok(v > prev && v <= 12);
    prev = v;
  }
  close(speedFromPower(0, 12), MIN_SPEED);
  close(speedFromPower(1, 12), 12);
  close(speedFromPower(2, 12), 12, 0); // power is clamped, so is the speed
});

test("the speed scale follows the server's max_speed", () => {
  close(speedFromPower(1, 8), 8);
  close(speedFromPower(1, 15), 15);
  // Same curve, stretched: half power is the same fraction of the range.
  const frac = (/** @type {number} */ max) => (speedFromPower(0.5, max) - MIN_SPEED) / (max - MIN_SPEED);
  close(frac(8), frac(15), 1e-12);
});

test('the tip stays inside the legal disc of the given radius', () => {
  assert.deepEqual(clampTip(0.1, 0.2, 0.5), [0.1, 0.2]);
  const [x, y] = clampTip(0.6, 0.8, 0.5);
  close(Math.hypot(x, y), 0.5, 1e-12);
  const [x2, y2] = clampTip(0.6, 0.8, 0.3);
  close(Math.hypot(x2, y2), 0.3, 1e-12);
  close(x2 / y2, 0.75, 1e-12); // the direction is kept
});

test('a portrait canvas stands the table on end, head at the top, and maps back exactly', () => {
  const v = makeView(TABLE, 400, 900);
  assert.equal(v.rotated, true);
  const [hx, hy] = v.toScreen(0, W / 2);
  const [fx, fy] = v.toScreen(L, W / 2);
  assert.ok(hy < fy && Math.abs(hx - fx) < 1e-9, 'head above foot');
  const [x, y] = v.toTable(...v.toScreen(2.1, 0.3));
  close(x, 2.1, 1e-12);
  close(y, 0.3, 1e-12);
  // A shot along +x (towards the foot) points down the screen.
  close(v.screenAngle(0), Math.PI / 2);
  assert.equal(makeView(TABLE, 900, 400).rotated, false);
});

test('the guide squirts like the server: Shot(…, tip=(x, 0)).squirt() with a ratio of 30', () => {
  // Values printed by the server's `Shot.squirt` for these side offsets.
  const server = [[0.1, 0.007430688007873146], [0.3, 0.021497946780529575],
    [0.5, 0.03291682876785524], [-0.5, -0.03291682876785524], [0, 0]];
  for (const [side, angle] of server) assert.ok(Math.abs(squirt(side, 30) - angle) < 1e-12);
  assert.ok(squirt(0.5, 60) < squirt(0.5, 30)); // a heavier tip end squirts more
});

test('a tip seen along a raised cue and seen level are one another\'s inverse', () => {
  const e = Math.PI / 4;
  const [side, height] = tipSeenLevel(0.2, -0.1, e);
  const back = tipAlongCue(side, height, e);
  assert.ok(Math.abs(back[0] - 0.2) < 1e-12 && Math.abs(back[1] + 0.1) < 1e-12);
  assert.deepEqual(tipSeenLevel(0.3, 0.1, 0), [0.3, 0.1]);
  // A jump through the centre (the computer's): centre ball along the cue.
  const along = tipAlongCue(...tipSeenLevel(0, 0, e), e);
  assert.ok(Math.abs(along[0]) < 1e-12 && Math.abs(along[1]) < 1e-12);
});
