/**
 * The client's model of the room, reduced from server messages (docs/protocol.md).
 *
 * `reduce(state, msg, now)` returns `{state, effects}`: a new state (the old one is never
 * modified) and the side effects the shell must carry out (feed the frame player, play a
 * sound, ask for a `sync`). Pure: no DOM, no sockets, so it is tested with `node --test`.
 */

import { groupBalls, isPractice } from './balls.js';
import { DEFAULT_LIMITS, DEFAULT_STREAM, readLimits, readStream } from './limits.js';
import { base64Bytes, decodeMotion } from './track.js';

const MM = 1000;

/** @typedef {{id: number, x: number, y: number, cel: number}} Ball metres */

/**
 * The client's model of one room (or of one replayed shot). Fields the server sends as
 * whole objects (`room`, `table`, `match`, `clock`) are kept as they came.
 * @typedef {object} RoomState
 * @property {string | null} roomId
 * @property {string} name
 * @property {string} connection connecting | open | reconnecting | closed
 * @property {{seat: number | null, role: string, name?: string}} me
 * @property {Readonly<import('./limits.js').StreamPacing>} stream the server's tick rate and
 *   frame pacing (replaced by `welcome`'s)
 * @property {Readonly<import('./limits.js').Limits>} limits what the server accepts (replaced
 *   by `welcome`'s `limits`)
 * @property {number | null} seq last room seq seen
 * @property {number} lastSyncAt
 * @property {any} room
 * @property {string} phase waiting | aiming | rolling | over
 * @property {any} table
 * @property {Ball[]} balls at rest
 * @property {number | null} shot id of the shot being shown
 * @property {{shot: number, t0: number, at: number} | null} rolling the shot a `state` said
 *   was being shown, how far in (`t0`, seconds) and when that came (`at`, local time)
 * @property {any} clock {seat, remaining, limit, at}: `at` = local time the message came
 * @property {any[]} grace
 * @property {any} match
 * @property {string} outcome last outcome in words
 * @property {any} lastResult
 * @property {{seat: number | null, name: string, text: string}[]} chat
 * @property {{seat: number, angle: number, power: number, tip: number[], at: number,
 *   elevation?: number} | null} aim relayed aim of the player at the table (a raised cue's
 *   `elevation`, its tip then as `shoot` names it)
 * @property {{code: string, message: string, ref: string | null, at: number} | null} error
 */

/**
 * @param {object} [opts]
 * @param {string | null} [opts.roomId]
 * @param {string} [opts.name]
 * @param {Readonly<import('./limits.js').StreamPacing>} [opts.stream] the stream's pacing when
 *   known before any `welcome` (a stored match's `stream`)
 * @returns {RoomState}
 */
export function initialState({ roomId = null, name = '', stream = DEFAULT_STREAM } = {}) {
  return {
    roomId,
    name,
    connection: 'connecting',
    me: { seat: null, role: 'spectator' },
    stream,
    limits: DEFAULT_LIMITS,
    seq: null,
    lastSyncAt: -Infinity,
    room: null,
    phase: 'waiting',
    table: null,
    balls: [],
    shot: null,
    rolling: null,
    clock: null,
    grace: [],
    match: null,
    outcome: '',
    lastResult: null,
    chat: [],
    aim: null,
    error: null,
  };
}

/**
 * Balls of a message in the wire format [id, x_mm, y_mm, cel] -> {id, x, y, cel} metres.
 * @param {number[][] | null | undefined} list
 * @returns {Ball[]}
 */
export function decodeBalls(list) {
  return (list ?? []).map(([id, x, y, cel]) => ({ id, x: x / MM, y: y / MM, cel }));
}

const SEQUENCED = new Set(['state', 'motion', 'shot_result', 'chat', 'presence']);
const SYNC_COOLDOWN = 1.0; // seconds between two sync requests

/**
 * Check the room sequence: returns [newSeq, gap]. `state` resets the counter (it is the
 * whole truth); a jump of more than one elsewhere is a gap.
 * @param {number | null} lastSeq
 * @param {Record<string, any>} msg
 * @returns {[number | null, boolean]}
 */
export function checkSeq(lastSeq, msg) {
  if (!SEQUENCED.has(msg.type) || typeof msg.seq !== 'number') return [lastSeq, false];
  if (msg.type === 'state' || lastSeq === null) return [msg.seq, false];
  if (msg.seq <= lastSeq) return [lastSeq, false]; // duplicate/old: ignore for counting
  return [msg.seq, msg.seq > lastSeq + 1];
}

/**
 * @typedef {{kind: string} & Record<string, any>} Effect what the shell must do
 *   (`sync`, `rest`, `shot`, `motion`, `result`; see reduce)
 */

/**
 * One server message into the state: the new state and the effects to carry out.
 * @param {RoomState} state
 * @param {any} msg
 * @param {number} [now] local time, seconds
 * @returns {{state: RoomState, effects: Effect[]}}
 */
export function reduce(state, msg, now = 0) {
  /** @type {Effect[]} */
  const effects = [];
  if (!msg || typeof msg !== 'object') return { state, effects };
  const [seq, gap] = checkSeq(state.seq, msg);
  const s = { ...state, seq };
  if (gap && now - s.lastSyncAt > SYNC_COOLDOWN) {
    // A frame gap alone is harmless, but a missed state/result is not: resync either way.
    effects.push({ kind: 'sync' });
    s.lastSyncAt = now;
  }
  HANDLERS.get(msg.type)?.(s, msg, now, effects);
  return { state: s, effects };
}

/**
 * One message type's part of `reduce`: `s` (a fresh copy of the state) is changed in place
 * and the effects are pushed onto `effects`.
 * @typedef {(s: RoomState, msg: any, now: number, effects: Effect[]) => void} Handler
 */

/** @type {Handler} */
function onWelcome(s, msg) {
  s.me = { seat: msg.seat ?? null, role: msg.role ?? 'spectator', name: msg.name };
  s.stream = readStream(msg, s.stream);
  s.limits = readLimits(msg.limits, s.limits);
  s.seq = msg.seq ?? s.seq;
  s.connection = 'open';
}

/** @type {Handler} */
function onState(s, msg, now, effects) {
  s.room = msg.room ?? s.room;
  s.phase = msg.phase ?? s.phase;
  s.table = msg.table ?? s.table;
  s.balls = decodeBalls(msg.balls);
  s.clock = msg.clock ? { ...msg.clock, at: now } : null;
  s.grace = msg.grace ?? [];
  s.match = msg.match ?? null;
  const said = [s.match?.last_outcome?.message, s.match?.notice].filter(Boolean);
  if (said.length) s.outcome = said.join(' ');
  if (s.phase === 'rolling' && msg.shot) {
    // A shot is being shown (we joined or came back during it): its `motion` follows,
    // to be played from this tick on, plus the time since.
    const t0 = msg.shot.tick / s.stream.tick_hz;
    s.rolling = { shot: msg.shot.id, t0, at: now };
    if (s.shot !== msg.shot.id) {
      s.shot = msg.shot.id;
      effects.push({ kind: 'shot', shot: msg.shot.id, tick: msg.shot.tick, t0,
        balls: s.balls });
    }
  } else {
    s.shot = null;
    s.rolling = null;
    effects.push({ kind: 'rest', balls: s.balls });
  }
  if (s.phase !== 'aiming') s.aim = null;
}

/** @type {Handler} */
function onMotion(s, msg, now, effects) {
  // A shot's whole motion (binary, decoded by net.js; a replay's comes in base64).
  let motion;
  try {
    motion = msg.tracks ? msg : decodeMotion(base64Bytes(msg.data));
  } catch {
    return; // not a motion this client can read: the next `state` shows the table
  }
  const joined = s.rolling && s.rolling.shot === motion.shot;
  const t0 = joined && s.rolling ? s.rolling.t0 + (now - s.rolling.at) : 0;
  s.shot = motion.shot;
  s.rolling = null;
  s.phase = 'rolling';
  s.aim = null;
  s.clock = null;
  effects.push({ kind: 'motion', motion, t0 });
}

/** @type {Handler} */
function onShotResult(s, msg, _now, effects) {
  s.lastResult = msg;
  s.outcome = msg.outcome?.message ?? s.outcome;
  if (s.match) {
    s.match = { ...s.match, score: msg.score ?? s.match.score };
  }
  effects.push({ kind: 'result', result: msg });
}

/** @type {Handler} */
function onAim(s, msg, now) {
  s.aim = { seat: msg.seat, angle: msg.angle, power: msg.power ?? 0,
    tip: msg.tip ?? [0, 0], at: now, ...(msg.elevation > 0 ? { elevation: msg.elevation } : {}) };
}

/** @type {Handler} */
function onChat(s, msg) {
  s.chat = [...s.chat, { seat: msg.seat, name: msg.name, text: msg.text }].slice(-50);
}

/** @type {Handler} */
function onPresence(s, msg) {
  if (s.room) s.room = { ...s.room, players: msg.players ?? s.room.players,
    spectators: msg.spectators ?? s.room.spectators };
  s.grace = msg.grace ?? s.grace;
}

/** @type {Handler} */
function onError(s, msg, now) {
  s.error = { code: msg.code, message: msg.message, ref: msg.ref ?? null, at: now };
}

/** @type {Map<string, Handler>} the message types the state follows; others change nothing */
const HANDLERS = new Map([
  ['welcome', onWelcome],
  ['state', onState],
  ['motion', onMotion],
  ['shot_result', onShotResult],
  ['aim', onAim],
  ['chat', onChat],
  ['presence', onPresence],
  ['error', onError],
]);

/**
 * Local connection status changes (from the socket wrapper).
 * @param {RoomState} state
 * @param {string} connection
 * @returns {RoomState}
 */
export function setConnection(state, connection) {
  return { ...state, connection };
}

// ---- derived views used by the HUD and the input ------------------------------------

/**
 * @param {RoomState} state
 * @param {number} seat
 * @returns {string | null}
 */
export function playerName(state, seat) {
  const p = state.room?.players?.find((/** @type {any} */ q) => q && q.seat === seat);
  return p?.name ?? null;
}

/**
 * Whose turn it is (seat) or null when nobody may act.
 * @param {RoomState} state
 * @returns {number | null}
 */
export function turnSeat(state) {
  if (state.phase !== 'aiming' || !state.match) return null;
  if (state.match.decision) return state.match.decision.seat;
  return state.match.turn ?? null;
}

/**
 * True when this client may act now (aim, shoot, place, call).
 * @param {RoomState} state
 */
export function isMyTurn(state) {
  return state.me.role === 'player' && state.me.seat !== null
    && turnSeat(state) === state.me.seat && !state.match?.over;
}

/**
 * Seconds left on the shot clock at local time `now` (null when no clock runs).
 * @param {RoomState} state
 * @param {number} now
 * @returns {number | null}
 */
export function clockRemaining(state, now) {
  if (!state.clock) return null;
  return Math.max(0, state.clock.remaining - (now - state.clock.at));
}

/**
 * The group ("solids" | "stripes") of a seat, or null while the table is open.
 * @param {RoomState} state
 * @param {number} seat
 * @returns {string | null}
 */
export function groupOf(state, seat) {
  const g = state.match?.groups;
  if (!g) return null;
  return g[seat] ?? g[String(seat)] ?? null;
}

/**
 * Ball ids still on the table for a seat's group.
 * @param {RoomState} state
 * @param {number} seat
 * @returns {number[]}
 */
export function ballsLeft(state, seat) {
  const group = groupOf(state, seat);
  if (!group) return [];
  const onTable = new Set(state.balls.map((b) => b.id));
  return groupBalls(group).filter((id) => onTable.has(id));
}

/**
 * Object balls no longer on the table (pocketed), in number order.
 * @param {RoomState} state
 * @returns {number[]}
 */
export function pocketedBalls(state) {
  if (!state.match || !state.table) return [];
  const onTable = new Set(state.balls.map((b) => b.id));
  if (state.match.kind === 'snooker') return []; // the frame's scoreboard tells it
  if (state.match.kind.startsWith('three_cushion')) return []; // no pockets
  const all = state.match.kind === 'nine_ball'
    ? [1, 2, 3, 4, 5, 6, 7, 8, 9]
    : [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15];
  return all.filter((id) => !onTable.has(id));
}

/**
 * The score line "Ana 1 – 0 Ben (race to 3)".
 * @param {RoomState} state
 */
export function scoreText(state) {
  const m = state.match;
  if (!m || !m.score) return '';
  const a = playerName(state, 0) ?? 'Player 1';
  const b = playerName(state, 1);
  if (isPractice(m.kind) || b === null) return `${a} · practice`;
  return `${a} ${m.score[0]} – ${m.score[1]} ${b} (race to ${m.race_to ?? 1})`;
}

/**
 * The match winner's name when the match is over, else null.
 * @param {RoomState} state
 */
export function winnerName(state) {
  const m = state.match;
  if (!m) return null;
  const w = m.match_winner ?? (m.over ? m.winner : null);
  if (state.phase !== 'over' && !m.match_over) return null;
  return w === null || w === undefined ? null : playerName(state, w);
}
