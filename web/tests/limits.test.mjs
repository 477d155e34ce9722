import { test } from 'node:test';
import assert from 'node:assert/strict';
import { DEFAULT_LIMITS, DEFAULT_STREAM, readLimits, readStream } from '../js/limits.js';
import { initialState, reduce } from '../js/state.js';
import { applyInputLimits } from '../js/ui.js';
import { routeOf } from '../js/routes.js';

const SERVER_LIMITS = { max_speed: 12.0, max_tip: 0.5, max_elevation: 1.3962634015954636,
  max_angle: 10.0, max_name: 24, max_chat: 200, cue_mass_ratio: 30.0 };

test('the defaults stand in for exactly the fields the server sends', () => {
  assert.deepEqual(Object.keys(DEFAULT_LIMITS).sort(), Object.keys(SERVER_LIMITS).sort());
  assert.deepEqual(Object.keys(DEFAULT_STREAM).sort(),
    ['frame_every', 'frames_per_message', 'tick_hz']);
  assert.ok(Object.isFrozen(DEFAULT_LIMITS) && Object.isFrozen(DEFAULT_STREAM));
});

test("the server's limits replace the defaults, field by field", () => {
  assert.equal(readLimits(undefined), DEFAULT_LIMITS);
  assert.equal(readLimits(null), DEFAULT_LIMITS);
  assert.equal(readLimits('nonsense'), DEFAULT_LIMITS);
  assert.deepEqual(readLimits({ ...SERVER_LIMITS, max_speed: 9, max_chat: 80 }),
    { ...SERVER_LIMITS, max_speed: 9, max_chat: 80 });
  const partial = readLimits({ max_name: 16 });
  assert.equal(partial.max_name, 16);
  assert.equal(partial.max_speed, DEFAULT_LIMITS.max_speed, 'a missing field keeps the fallback');
  assert.ok(Object.isFrozen(partial));
  assert.equal(DEFAULT_LIMITS.max_name, 24, 'the defaults are never modified');
});

test('malformed limits are ignored rather than breaking the inputs', () => {
  const limits = readLimits({ max_speed: -1, max_tip: 'big', max_name: 0, max_chat: NaN,
    max_angle: Infinity });
  assert.deepEqual(limits, DEFAULT_LIMITS);
  assert.equal(readLimits({ max_name: 20.7 }).max_name, 20, 'lengths are whole characters');
});

test('an earlier server answer is the fallback for a later partial one', () => {
  const first = readLimits({ max_speed: 9 });
  assert.equal(readLimits({ max_chat: 50 }, first).max_speed, 9);
  assert.equal(readLimits(undefined, first), first);
});

test('stream pacing from a welcome (top level) or a match detail (`stream`)', () => {
  assert.equal(readStream(undefined), DEFAULT_STREAM);
  const welcome = { type: 'welcome', tick_hz: 240, frame_every: 12, frames_per_message: 2 };
  assert.deepEqual(readStream(welcome), { tick_hz: 240, frame_every: 12, frames_per_message: 2 });
  const detail = { id: 4, stream: { tick_hz: 60, frame_every: 3, frames_per_message: 4 } };
  assert.equal(readStream(detail.stream).tick_hz, 60);
  assert.equal(readStream({ tick_hz: 0 }).tick_hz, DEFAULT_STREAM.tick_hz);
});

test('welcome: limits and tick rate come from the server; without them the defaults stay', () => {
  const s0 = initialState();
  assert.equal(s0.limits, DEFAULT_LIMITS);
  assert.equal(s0.stream, DEFAULT_STREAM);
  const old = reduce(s0, { type: 'welcome', seat: 0, role: 'player', seq: 1, tick_hz: 120,
    frame_every: 6 }).state;
  assert.deepEqual(old.limits, DEFAULT_LIMITS);
  const s1 = reduce(s0, { type: 'welcome', seat: 0, role: 'player', seq: 1, tick_hz: 60,
    frame_every: 3, frames_per_message: 4,
    limits: { ...SERVER_LIMITS, max_speed: 8, max_chat: 120 } }).state;
  assert.equal(s1.limits.max_speed, 8);
  assert.equal(s1.limits.max_chat, 120);
  assert.equal(s1.stream.tick_hz, 60);
  // A reconnection's welcome without limits keeps what the server said before.
  const s2 = reduce(s1, { type: 'welcome', seat: 0, role: 'player', seq: 9 }).state;
  assert.equal(s2.limits.max_speed, 8);
  assert.equal(s2.stream.tick_hz, 60);
});

test('joining a shot under way starts at its tick in seconds of the server clock', () => {
  const s = reduce(initialState(), { type: 'welcome', seat: 0, role: 'player', seq: 1,
    tick_hz: 60 }).state;
  const { effects } = reduce(s, { type: 'state', seq: 2, phase: 'rolling', balls: [],
    shot: { id: 4, tick: 120 } });
  const shot = effects.find((e) => e.kind === 'shot');
  assert.equal(shot?.t0, 2);
});

/**
 * A stand-in for the document: inputs with `data-limit` and their maxLength.
 * @param {...string} limits
 */
function fakeRoot(...limits) {
  const inputs = limits.map((limit) => ({ dataset: { limit }, maxLength: -1 }));
  return { inputs, querySelectorAll: () => inputs };
}

test('text fields take their maxlength from the limit they name', () => {
  const root = fakeRoot('max_name', 'max_chat', 'max_name');
  applyInputLimits(DEFAULT_LIMITS, /** @type {any} */ (root));
  assert.deepEqual(root.inputs.map((i) => i.maxLength), [24, 200, 24]);
  applyInputLimits(readLimits({ max_name: 12, max_chat: 80 }), /** @type {any} */ (root));
  assert.deepEqual(root.inputs.map((i) => i.maxLength), [12, 80, 12]);
  const odd = fakeRoot('max_tip', 'no_such_limit');
  applyInputLimits(DEFAULT_LIMITS, /** @type {any} */ (odd));
  assert.deepEqual(odd.inputs.map((i) => i.maxLength), [-1, -1], 'only whole positive numbers');
});

test('the address picks the screen', () => {
  assert.deepEqual(routeOf('/'), { screen: 'lobby' });
  assert.deepEqual(routeOf('/r/k3J9x_Qa2LmP'), { screen: 'table', roomId: 'k3J9x_Qa2LmP' });
  assert.deepEqual(routeOf('/r/k3J9x_Qa2LmP/'), { screen: 'table', roomId: 'k3J9x_Qa2LmP' });
  assert.deepEqual(routeOf('/m/42'), { screen: 'replay', matchId: '42' });
  assert.deepEqual(routeOf('/m/a%20b'), { screen: 'replay', matchId: 'a b' });
  assert.deepEqual(routeOf('/m/%E0%A4%A'), { screen: 'replay', matchId: '%E0%A4%A' });
  assert.deepEqual(routeOf('/r/bad!id'), { screen: 'lobby' });
  assert.deepEqual(routeOf('/elsewhere'), { screen: 'lobby' });
});
