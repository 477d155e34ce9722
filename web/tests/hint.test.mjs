import { test } from 'node:test';
import assert from 'node:assert/strict';
import { powerFromSpeed, spinWords, describeHint } from '../js/hint.js';
import { speedFromPower, MIN_SPEED } from '../js/geometry.js';

test('the hint draws the cue back by the power that gives its speed', () => {
  for (const speed of [MIN_SPEED, 0.8, 2.5, 6.0, 11.9, 12.0]) {
    const power = powerFromSpeed(speed, 12);
    assert.ok(power >= 0 && power <= 1);
    assert.ok(Math.abs(speedFromPower(power, 12) - speed) < 1e-9, `${speed}`);
  }
  assert.equal(powerFromSpeed(0.01, 12), 0);
  assert.equal(powerFromSpeed(20, 12), 1);
});

test('spin in words: follow or draw, then side; a tiny offset is centre ball', () => {
  assert.equal(spinWords([0, 0]), 'centre ball');
  assert.equal(spinWords([0.02, -0.03]), 'centre ball');
  assert.equal(spinWords([0, 0.35]), 'follow');
  assert.equal(spinWords([0, -0.35]), 'draw');
  assert.equal(spinWords([0.3, 0.15]), 'follow and right side');
  assert.equal(spinWords([-0.3, 0]), 'left side');
});

test('the caption says what the plan is, its odds for a pot, its power (%) and spin', () => {
  const pct = `power ${Math.round(powerFromSpeed(2.345, 12) * 100)} %`;
  const base = { level: 'pro', place: null, call: null, angle: 0, speed: 2.345,
    tip: /** @type {[number, number]} */ ([0, -0.35]), target: 3, pocket: 2, chance: 0.85 };
  assert.equal(describeHint({ ...base, kind: 'pot' }, 12),
    `Pot the 3 (85 % of the computer's trials went in): ${pct}, draw.`);
  assert.equal(describeHint({ ...base, kind: 'safety', tip: [0, 0] }, 12),
    `Play safe: ${pct}, centre ball.`);
  assert.equal(describeHint({ ...base, kind: 'kick', chance: null }, 12),
    `Kick at it off a cushion: ${pct}, draw.`);
  assert.equal(describeHint({ ...base, kind: 'pot', via: 'direct' }, 12),
    `Pot the 3 (85 % of the computer's trials went in): ${pct}, draw.`);
  assert.equal(describeHint({ ...base, kind: 'pot', via: 'bank', chance: 0.4 }, 12),
    `Bank the 3 off a cushion (40 % of the computer's trials went in): ${pct}, draw.`);
  assert.equal(describeHint({ ...base, kind: 'pot', via: 'combo', target: 9 }, 12),
    `Pot the 9 in a combination (85 % of the computer's trials went in): ${pct}, draw.`);
  assert.equal(describeHint({ ...base, kind: 'pot', via: 'carom', target: 2 }, 12),
    `Carom the 2 off another ball (85 % of the computer's trials went in): ${pct}, draw.`);
});

test('the break on a racked table says so, with its power', () => {
  const hint = { level: 'pro', kind: 'break', place: /** @type {[number, number]} */ ([0.6, 0.9]),
    call: null, angle: 0, speed: 10, tip: /** @type {[number, number]} */ ([0, 0]), target: 1,
    pocket: null, chance: 0.3 };
  assert.equal(describeHint(hint, 12), `Break: power ${Math.round(powerFromSpeed(10, 12) * 100)} %, centre ball.`);
});
