import { test } from 'node:test';
import assert from 'node:assert/strict';
import {
  initialState, reduce, checkSeq, decodeBalls, isMyTurn, turnSeat, clockRemaining, ballsLeft,
  pocketedBalls, scoreText, winnerName,
} from '../js/state.js';
import { decodeMotion } from '../js/track.js';
import { encodeMotion } from './motion.mjs';

const room = {
  room_id: 'abc', game: 'eight_ball', race_to: 3, seats: 2, status: 'playing',
  players: [{ seat: 0, name: 'Ana', connected: true }, { seat: 1, name: 'Ben', connected: true }],
  spectators: 0,
};
const match = (extra = {}) => ({ kind: 'eight_ball', race_to: 3, score: [1, 0], turn: 0,
  ball_in_hand: null, groups: null, requires_call: false, called_pocket: null, decision: null,
  over: false, winner: null, last_outcome: null, ...extra });
/** @type {(seq: number, extra?: object) => Record<string, any>} */
const stateMsg = (seq, extra = {}) => ({ type: 'state', seq, room, phase: 'aiming',
  table: { length: 2.54, width: 1.27, ball_radius: 0.028575 },
  balls: [[0, 635, 635, 0], [1, 1905, 635, 3], [9, 2000, 600, 0]], shot: null,
  clock: { seat: 0, remaining: 50, limit: 60 }, grace: [], match: match(), ...extra });

/**
 * Reduce messages [msg, now?] in order from `start`.
 * @param {[any, number?][]} msgs
 * @param {import('../js/state.js').RoomState} [start]
 */
function run(msgs, start = initialState()) {
  let s = start;
  const effects = [];
  for (const [msg, now] of msgs) {
    const r = reduce(s, msg, now ?? 0);
    s = r.state;
    effects.push(...r.effects);
  }
  return { s, effects };
}

test('wire balls in millimetres become metres', () => {
  assert.deepEqual(decodeBalls([[3, 1270, 635, 15]]), [{ id: 3, x: 1.27, y: 0.635, cel: 15 }]);
});

test('welcome then state: seat, table, balls at rest, my turn', () => {
  const { s, effects } = run([
    [{ type: 'welcome', seat: 0, role: 'player', name: 'Ana', seq: 4, tick_hz: 120,
      frame_every: 6 }],
    [stateMsg(4)],
  ]);
  assert.equal(s.me.seat, 0);
  assert.equal(s.connection, 'open');
  assert.equal(s.balls.length, 3);
  assert.equal(s.balls[1].x, 1.905);
  assert.ok(isMyTurn(s));
  assert.deepEqual(effects.map((e) => e.kind), ['rest']);
});

test('a spectator never has the turn', () => {
  const { s } = run([[{ type: 'welcome', seat: null, role: 'spectator', seq: 1 }],
    [stateMsg(1)]]);
  assert.equal(turnSeat(s), 0);
  assert.equal(isMyTurn(s), false);
});

test('a shot`s motion starts playback at its strike; the table rolls', () => {
  const motion = decodeMotion(encodeMotion({ seq: 2, shot: 7, duration: 0.1,
    tracks: [{ id: 0, t: [0, 0.1], x: [0.635, 0.76], y: [0.635, 0.635] }] }));
  const { s, effects } = run([
    [{ type: 'welcome', seat: 1, role: 'player', seq: 1, tick_hz: 120 }],
    [stateMsg(1)],
    [motion, 5],
  ]);
  assert.deepEqual(effects.map((e) => e.kind), ['rest', 'motion']);
  assert.equal(effects[1].motion, motion);
  assert.equal(effects[1].t0, 0);
  assert.equal(s.phase, 'rolling');
  assert.equal(s.shot, 7);
  assert.equal(s.clock, null);
});

test('a replay`s motion line carries the same bytes in base64', () => {
  const bytes = encodeMotion({ seq: 1, shot: 3, duration: 0.5,
    tracks: [{ id: 0, t: [0, 0.5], x: [0.5, 1], y: [0.5, 0.5] }] });
  const data = Buffer.from(bytes).toString('base64');
  const { effects } = run([[{ type: 'motion', seq: 1, shot: 3, data }]]);
  assert.equal(effects[0].kind, 'motion');
  assert.deepEqual(effects[0].motion, decodeMotion(bytes));
  const bad = run([[{ type: 'motion', seq: 1, shot: 3, data: 'AAAA' }]]);
  assert.deepEqual(bad.effects, [], 'an unreadable motion changes nothing');
});

test('a sequence gap asks for a sync (once per cooldown); a state resets the count', () => {
  assert.deepEqual(checkSeq(5, { type: 'motion', seq: 6 }), [6, false]);
  assert.deepEqual(checkSeq(5, { type: 'motion', seq: 8 }), [8, true]);
  assert.deepEqual(checkSeq(5, { type: 'aim' }), [5, false]);
  assert.deepEqual(checkSeq(9, { type: 'state', seq: 3 }), [3, false]);
  const { effects } = run([
    [stateMsg(10), 0],
    [{ type: 'chat', seq: 13, seat: 0, name: 'Ana', text: 'a' }, 1.0],
    [{ type: 'chat', seq: 15, seat: 0, name: 'Ana', text: 'b' }, 1.2],
    [{ type: 'chat', seq: 18, seat: 0, name: 'Ana', text: 'c' }, 2.5],
  ]);
  assert.equal(effects.filter((e) => e.kind === 'sync').length, 2);
});

test('aim is relayed', () => {
  const { s } = run([
    [stateMsg(1)],
    [{ type: 'aim', seat: 1, angle: 1.5, power: 0.3, tip: [0, 0.1] }, 3],
  ]);
  assert.deepEqual(s.aim, { seat: 1, angle: 1.5, power: 0.3, tip: [0, 0.1], at: 3 });
});

test('shot_result sets the outcome in words and the score', () => {
  const { s } = run([[stateMsg(1)], [{ type: 'shot_result', seq: 2, shot: 1, cause: 'shot',
    outcome: { message: 'Foul: scratch. Ball in hand for Ben.' }, score: [1, 1],
    match_over: false }]]);
  assert.equal(s.outcome, 'Foul: scratch. Ball in hand for Ben.');
  assert.equal(scoreText(s), 'Ana 1 – 1 Ben (race to 3)');
});

test('the shot clock counts down locally from the state', () => {
  const { s } = run([[stateMsg(1), 100]]);
  assert.equal(clockRemaining(s, 100), 50);
  assert.equal(clockRemaining(s, 110.5), 39.5);
  assert.equal(clockRemaining(s, 500), 0);
});

test('groups: balls still to pot per seat, pocketed balls, winner', () => {
  const { s } = run([[stateMsg(1, { match: match({ groups: { 0: 'solids', 1: 'stripes' } }) })]]);
  assert.deepEqual(ballsLeft(s, 0), [1]);
  assert.deepEqual(ballsLeft(s, 1), [9]);
  assert.equal(pocketedBalls(s).length, 13);
  assert.equal(winnerName(s), null);
  const over = run([[stateMsg(2, { phase: 'over',
    match: match({ over: true, winner: 1, match_winner: 1 }) })]]).s;
  assert.equal(winnerName(over), 'Ben');
});

test('chat keeps the last 50 lines; errors are kept with their time', () => {
  /** @type {[any, number?][]} */
  const msgs = [];
  for (let i = 0; i < 60; i++) {
    msgs.push([{ type: 'chat', seq: i + 2, seat: 1, name: 'Ben', text: `m${i}` }]);
  }
  msgs.push([{ type: 'error', code: 'not_your_turn', message: "It is Ben's turn.", ref: 'shoot' },
    7]);
  const { s } = run([[stateMsg(1)], ...msgs]);
  assert.equal(s.chat.length, 50);
  assert.equal(s.chat[49].text, 'm59');
  assert.ok(s.error);
  assert.equal(s.error.code, 'not_your_turn');
  assert.equal(s.error.at, 7);
});

test('joining while a shot is shown plays its motion from the state`s tick on', () => {
  const motion = decodeMotion(encodeMotion({ seq: 2, shot: 4, duration: 6,
    tracks: [{ id: 0, t: [0], x: [1], y: [0.5] }] }));
  const { effects } = run([
    [stateMsg(5, { phase: 'rolling', shot: { id: 4, seat: 0, tick: 120, ticks: 700 },
      clock: null }), 10],
    [motion, 10.25],
  ]);
  assert.equal(effects[0].kind, 'shot');
  assert.equal(effects[0].tick, 120);
  assert.equal(effects[0].balls.length, 3);
  assert.equal(effects[1].kind, 'motion');
  assert.equal(effects[1].t0, 1.25, '1 s in when the state was sent, and 0.25 s since');
});

test('garbage messages change nothing', () => {
  const s0 = run([[stateMsg(1)]]).s;
  for (const bad of [null, 42, 'x', { type: 'nope' }, {}]) {
    const r = reduce(s0, bad, 0);
    assert.deepEqual(r.effects, []);
    assert.deepEqual(r.state.balls, s0.balls);
  }
});

test('groups as the rules send them (a list by seat) and a notice beside the outcome', () => {
  const { s } = run([[stateMsg(1, { match: match({ groups: ['stripes', 'solids'],
    last_outcome: { message: 'Ben fouls.' }, notice: 'Ana declares a push out.' }) })]]);
  assert.deepEqual(ballsLeft(s, 0), [9]);
  assert.deepEqual(ballsLeft(s, 1), [1]);
  assert.equal(s.outcome, 'Ben fouls. Ana declares a push out.');
});


test("a raised cue's relayed aim keeps its elevation (a level one has none)", () => {
  const { s } = run([
    [stateMsg(1)],
    [{ type: 'aim', seat: 1, angle: 1.5, power: 0.3, tip: [0.2, 0.6], elevation: 0.7 }, 3],
  ]);
  assert.equal(s.aim?.elevation, 0.7);
  const level = run([[stateMsg(1)], [{ type: 'aim', seat: 1, angle: 1.5, power: 0.3, tip: [0, 0.1] }, 4]]);
  assert.equal(level.s.aim && 'elevation' in level.s.aim, false);
});
