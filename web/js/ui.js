/**
 * The DOM around the canvas: lobby list, HUD (players, turn and clock, groups and balls
 * left, pocketed balls, score, outcome, connection), chat, buttons, winner banner.
 * Written to only touch the DOM when a shown value changes.
 */

import { ballColor, isStripe, groupBalls, isPractice } from './balls.js';
import {
  playerName, turnSeat, isMyTurn, clockRemaining, groupOf, ballsLeft, pocketedBalls,
  scoreText, winnerName,
} from './state.js';
import { tidyOutcome, decisionLabel, countdown } from './words.js';
import { icon } from './icons.js';

/** Seconds left on the shot clock from which it turns urgent (colour, ring, tick). */
export const URGENT_AT = 10;

/**
 * The element with this id; index.html has every id the screens use, so a missing one is
 * a programming error and fails loudly here rather than later on `null`.
 * @param {string} id
 * @returns {HTMLElement}
 */
export const $ = (id) => {
  const el = document.getElementById(id);
  if (!el) throw new Error(`index.html has no #${id}`);
  return el;
};

/**
 * @param {string} id
 * @returns {HTMLInputElement}
 */
export const $input = (id) => /** @type {HTMLInputElement} */ ($(id));

/**
 * @param {string} id
 * @returns {HTMLSelectElement}
 */
export const $select = (id) => /** @type {HTMLSelectElement} */ ($(id));

/**
 * Text fields whose length the server limits say which limit in `data-limit` (e.g.
 * `data-limit="max_name"`): set their `maxlength` from `limits`.
 * @param {Readonly<import('./limits.js').Limits>} limits
 * @param {ParentNode} [root]
 */
export function applyInputLimits(limits, root = document) {
  for (const el of root.querySelectorAll('input[data-limit]')) {
    const input = /** @type {HTMLInputElement} */ (el);
    const key = /** @type {keyof import('./limits.js').Limits} */ (input.dataset.limit);
    const n = limits[key];
    if (Number.isInteger(n) && n > 0 && input.maxLength !== n) input.maxLength = n;
  }
}

/**
 * @param {Element | null} el
 * @param {string} text
 */
export function setText(el, text) {
  if (el && el.textContent !== text) el.textContent = text;
}

/**
 * @param {HTMLElement | null} el
 * @param {boolean} hidden
 */
function setHidden(el, hidden) {
  if (el && el.hidden !== hidden) el.hidden = hidden;
}

/**
 * A small ball chip for the HUD (colour, stripe, number).
 * @param {number} id
 */
export function miniBall(id) {
  const el = document.createElement('span');
  el.className = 'mini';
  const c = ballColor(id);
  el.style.background = isStripe(id)
    ? `linear-gradient(#f7f3e6 0 22%, ${c} 22% 78%, #f7f3e6 78%)` : c;
  el.textContent = id ? String(id) : '';
  if (isStripe(id)) el.classList.add('stripe');
  if (id === 8) el.classList.add('eight');
  if (id === 8 || [2, 4, 7].includes(id)) el.style.color = '#fff';
  el.title = `Ball ${id}`;
  el.dataset.ball = String(id);
  return el;
}

/**
 * @param {HTMLElement | null} el
 * @param {number[]} ids
 */
function setBalls(el, ids) {
  if (!el) return;
  const key = ids.join(',');
  if (el.dataset.key === key) return;
  el.dataset.key = key;
  el.replaceChildren(...ids.map(miniBall));
}

/** @type {Record<string, string>} */
const GAME_NAMES = {
  eight_ball: '8-ball', nine_ball: '9-ball', practice: 'Practice', snooker: 'Snooker',
  snooker_practice: 'Snooker practice',
  three_cushion_practice: 'Three-cushion practice',
  three_cushion: 'Three-cushion',
};

/**
 * Fill the lobby's room list.
 * @param {HTMLElement} list
 * @param {any[]} rooms `GET /api/rooms`'s rooms
 * @param {{onJoin: (roomId: string) => void, onWatch: (roomId: string) => void}} actions
 */
export function renderRooms(list, rooms, { onJoin, onWatch }) {
  const items = rooms.map((r) => {
    const li = document.createElement('li');
    li.dataset.room = r.room_id;
    const what = document.createElement('div');
    what.className = 'what';
    /** @type {(string | null)[]} */
    const seats = r.players ?? [];
    const players = seats.map((p) => p ?? 'free seat').join(' vs ');
    const title = document.createElement('div');
    title.textContent = `${GAME_NAMES[r.game] ?? r.game}`
      + (!isPractice(r.game) ? ` · race to ${r.race_to}` : '') + (r.ranked ? ' · ranked' : '');
    const who = document.createElement('div');
    who.className = 'who';
    who.textContent = `${players}${r.spectators ? ` · ${r.spectators} watching` : ''}`;
    what.append(title, who);
    const tag = document.createElement('span');
    tag.className = `tag ${r.status}`;
    tag.textContent = r.status;
    li.append(what, tag);
    if (seats.some((p) => p === null)) {
      const join = document.createElement('button');
      join.textContent = 'Join';
      join.className = 'primary';
      join.dataset.testid = 'join';
      join.addEventListener('click', () => onJoin(r.room_id));
      li.append(join);
    }
    const watch = document.createElement('button');
    watch.textContent = 'Watch';
    watch.dataset.testid = 'watch';
    watch.addEventListener('click', () => onWatch(r.room_id));
    li.append(watch);
    return li;
  });
  list.replaceChildren(...items);
}

/**
 * A sound on/off button for `audio`; `remember(muted)` keeps the choice.
 * @param {HTMLElement} button
 * @param {import('./audio.js').TableAudio} audio
 * @param {(muted: boolean) => void} remember
 */
export function bindMute(button, audio, remember) {
  const show = () => {
    button.textContent = audio.muted ? 'Sound off' : 'Sound on';
    button.setAttribute('aria-pressed', String(audio.muted));
  };
  show();
  button.addEventListener('click', () => {
    audio.unlock();
    audio.setMuted(!audio.muted);
    remember(audio.muted);
    show();
  });
}

/**
 * "Ana 2–1 Ben" style summary of a stored match.
 * @param {{players?: string[], score?: number[]}} m
 */
export function matchLine(m) {
  const [a, b] = m.players ?? [];
  const [sa, sb] = m.score ?? [0, 0];
  return `${a ?? '?'} ${sa}–${sb} ${b ?? '?'}`;
}

/**
 * Fill the lobby's list of finished matches, each with a link to watch it again.
 * @param {HTMLElement} list
 * @param {any[]} matches `GET /api/matches`'s matches
 */
export function renderHistory(list, matches) {
  const items = matches.map((m) => {
    const li = document.createElement('li');
    li.dataset.testid = 'history-match';
    li.dataset.match = String(m.id);
    const what = document.createElement('div');
    what.className = 'what';
    const title = document.createElement('div');
    title.textContent = matchLine(m);
    const who = document.createElement('div');
    who.className = 'who';
    const when = m.finished_at ? new Date(m.finished_at * 1000).toLocaleString() : '';
    const abandoned = m.status === 'abandoned';
    li.dataset.status = m.status ?? 'finished';
    who.textContent = [GAME_NAMES[m.game] ?? m.game,
      abandoned ? 'abandoned' : m.winner_name ? `${m.winner_name} won` : '',
      m.shots ? `${m.shots} shot${m.shots === 1 ? '' : 's'}` : 'no shot played', when]
      .filter(Boolean).join(' · ');
    what.append(title, who);
    li.append(what);
    if (abandoned) {
      const tag = document.createElement('span');
      tag.className = 'tag abandoned';
      tag.textContent = 'abandoned';
      li.append(tag);
    }
    if (m.shots > 0) {
      const watch = document.createElement('a');
      watch.href = `/m/${m.id}`;
      watch.className = 'button';
      watch.textContent = 'Watch';
      watch.dataset.testid = 'watch-match';
      li.append(watch);
    }
    return li;
  });
  list.replaceChildren(...items);
}

/**
 * Update the HUD from the state (called every frame; cheap when nothing changed).
 * @param {import('./state.js').RoomState} state
 * @param {number} now
 */
export function renderHud(state, now) {
  const mySeat = state.me.role === 'player' ? state.me.seat : null;
  const turn = turnSeat(state);
  for (const seat of [0, 1]) renderPlayer(state, seat, seat === mySeat, turn === seat);
  const winner = winnerName(state);
  const turnEl = $('turn');
  setText(turnEl, turnText(state, mySeat, turn, winner));
  turnEl.dataset.seat = turn === null ? '' : String(turn);
  turnEl.dataset.phase = state.phase;
  turnEl.classList.toggle('mine', isMyTurn(state));
  renderClock(state, clockRemaining(state, now));
  setText($('score'), scoreText(state));
  setText($('outcome'), outcomeText(state));
  renderTray(state);
  const conn = $('connection');
  setText(conn, state.connection);
  conn.className = `conn ${state.connection}`;
  setText($('role'), state.me.role === 'player' ? `seat ${(state.me.seat ?? 0) + 1}` : 'spectator');
  renderRematch(state);
  renderWaysOn(state);
  renderDrill(state);
  renderActions(state);
  renderWinner(winner);
  const error = state.error && now - state.error.at < 4 ? state.error.message : '';
  setText($('toast'), error);
  setHidden($('toast'), !error);
}

/**
 * A seat's box: the name (or that it waits for a player), connected or away, the turn,
 * the group and the balls left.
 * @param {import('./state.js').RoomState} state
 * @param {number} seat
 * @param {boolean} mine this page's seat
 * @param {boolean} turn the seat to play
 */
function renderPlayer(state, seat, mine, turn) {
  const el = $(`player-${seat}`);
  const p = state.room?.players?.find((/** @type {any} */ q) => q && q.seat === seat);
  const exists = seat < (state.room?.seats ?? 2);
  setHidden(el, !exists);
  const name = p?.name ?? (exists ? 'waiting for a player…' : '');
  const pname = el.querySelector('.pname');
  setText(pname, name + (mine ? ' (you)' : ''));
  if (pname instanceof HTMLElement && pname.title !== name) pname.title = name;
  el.classList.toggle('connected', !!p?.connected);
  el.classList.toggle('absent', !!p && !p.connected);
  el.classList.toggle('turn', turn);
  const group = groupOf(state, seat);
  setText(el.querySelector('.group'), group ?? '');
  setBalls(el.querySelector('.left'), ballsLeft(state, seat));
}

/**
 * The line over the table: waiting, over, rolling, or whose turn and what it holds.
 * @param {import('./state.js').RoomState} state
 * @param {number | null} mySeat
 * @param {number | null} turn
 * @param {string | null} winner
 */
function turnText(state, mySeat, turn, winner) {
  const m = state.match;
  if (state.phase === 'waiting') return 'Waiting for an opponent…';
  if (state.room?.abandoned) return 'Match abandoned: both players left';
  if (state.phase === 'over' || winner) return winner ? `${winner} wins the match` : 'Match over';
  if (state.phase === 'rolling') {
    const shooter = m ? playerName(state, m.turn) : null;
    return shooter ? `${shooter} shoots…` : 'Balls rolling…';
  }
  if (turn === null) return 'Connecting…';
  const who = turn === mySeat ? 'Your turn' : `${playerName(state, turn) ?? 'Player'}'s turn`;
  const extras = turnExtras(m, turn === mySeat);
  return `${who}${extras.length ? ` · ${extras.join(' · ')}` : ''}`;
}

/**
 * What the turn holds: a choice, ball in hand, a pocket to call, the break.
 * @param {any} m the match
 * @param {boolean} mine
 * @returns {string[]}
 */
function turnExtras(m, mine) {
  const extras = [];
  if (m?.decision) extras.push(mine ? 'your choice' : 'choosing');
  else if (m?.ball_in_hand) extras.push('ball in hand');
  if (m?.requires_call && m?.called_pocket == null) extras.push('call a pocket for the 8');
  if (m?.breaking && !m?.decision) extras.push('break');
  return extras;
}

/**
 * The shot clock: a badge with a ring that empties, urgent in the last seconds. (On a
 * room's first break more than `limit` is left: the ring stays full until it is not.)
 * @param {import('./state.js').RoomState} state
 * @param {number | null} left seconds
 */
function renderClock(state, left) {
  const clockEl = $('shot-clock');
  setHidden(clockEl, left === null);
  const urgent = left !== null && left <= URGENT_AT;
  clockEl.classList.toggle('urgent', urgent);
  clockEl.dataset.urgent = String(urgent);
  const limit = state.clock?.limit || state.room?.shot_clock || 1;
  const frac = left === null ? 1 : Math.max(0, Math.min(1, left / limit));
  clockEl.style.setProperty('--left', frac.toFixed(3));
  setText(clockEl.querySelector('.secs'), left !== null ? countdown(left) : '');
}

/**
 * The words under the HUD: the last outcome, or what the table waits for.
 * @param {import('./state.js').RoomState} state
 */
function outcomeText(state) {
  if (state.room?.abandoned) {
    return 'Both players left the table and nobody came back: the match was abandoned.';
  }
  return tidyOutcome(state.outcome)
    || (state.phase === 'waiting' ? 'Send the link to a friend to start.' : '');
}

/**
 * Concede (a match under way), re-rack (practice), push-out (when it may be declared).
 * @param {import('./state.js').RoomState} state
 */
function renderActions(state) {
  const m = state.match;
  const isPlayer = state.me.role === 'player';
  const practice = isPractice(m?.kind) || isPractice(state.room?.game);
  setHidden($('concede'), !(isPlayer && !practice && (state.phase === 'aiming'
    || state.phase === 'rolling')));
  setHidden($('rerack'), !(isPlayer && practice));
  setHidden($('push-out'), !(isMyTurn(state) && m?.push_out_available && !m?.push_out_declared));
}

/**
 * The match winner's banner.
 * @param {string | null} winner
 */
function renderWinner(winner) {
  const banner = $('banner');
  setHidden(banner, !winner);
  if (winner && banner.dataset.winner !== winner) {
    banner.dataset.winner = winner;
    const words = document.createElement('span');
    words.textContent = `${winner} wins the match!`;
    banner.replaceChildren(icon('trophy', 34), words);
  }
}

/**
 * Rematch: who asked, and the button that asks or accepts.
 * @param {import('./state.js').RoomState} state
 */
function renderRematch(state) {
  const button = $('rematch');
  const info = $('rematch-state');
  const over = state.phase === 'over' && !state.room?.abandoned;
  const isPlayer = state.me.role === 'player' && state.me.seat !== null;
  /** @type {number[]} */
  const votes = over ? state.room?.rematch ?? [] : [];
  const mine = isPlayer && votes.includes(/** @type {number} */ (state.me.seat));
  const others = votes.filter((s) => s !== state.me.seat);
  setHidden(button, !(isPlayer && over));
  const label = mine ? 'Rematch asked' : others.length ? 'Accept rematch' : 'Rematch';
  setText(button, label);
  /** @type {HTMLButtonElement} */ (button).disabled = mine;
  button.classList.toggle('primary', !mine && others.length > 0);
  let text = '';
  if (mine) {
    const waiting = (state.room?.players ?? []).filter((/** @type {any} */ p) =>
      p.seat !== state.me.seat && !votes.includes(p.seat)).map((/** @type {any} */ p) => p.name);
    text = `You asked for a rematch. Waiting for ${waiting.join(' and ') || 'the others'}…`;
  } else if (others.length) {
    const names = others.map((s) => playerName(state, s) ?? 'A player');
    text = `${names.join(' and ')} ${isPlayer ? 'asks you for' : 'asks for'} a rematch.`;
  }
  setText(info, text);
  setHidden(info, !text);
  info.dataset.votes = votes.join(',');
}

/**
 * A drill's table (`state.room.drill`): where it comes from, its par, and once the first
 * shot is played whether it made the position; a link back to the match's analysis.
 * @param {import('./state.js').RoomState} state
 */
function renderDrill(state) {
  const drill = state.room?.drill;
  setHidden($('drill'), !drill);
  if (!drill) return;
  setHidden($('drill-back'), drill.kind !== 'position');
  if (drill.kind === 'ghost' || drill.kind === 'lineup') {
    setText($('drill-text'), drill.kind === 'ghost' ? ghostWords(drill) : lineupWords(drill));
    $('drill-text').dataset.made = drill.done ? String(drill.won) : '';
    return;
  }
  const par = `Par: the strongest computer level pots from here ${Math.round(drill.par * 100)} % of the time.`;
  const result = drill.made === null || drill.made === undefined ? `Drill: shot ${drill.n} again. ${par}`
    : drill.made ? `Made it: a ball pocketed without a foul. ${par}` : `Not this time. ${par}`;
  setText($('drill-text'), result);
  $('drill-text').dataset.made = drill.made === null || drill.made === undefined ? '' : String(drill.made);
  const back = `/m/${drill.match}?analyse=1`;
  const link = $('drill-back');
  if (link.getAttribute('href') !== back) link.setAttribute('href', back);
}

/**
 * Ghost 9-ball's words: the rule, then the balls pocketed and who won the rack.
 * @param {{score: number, done: boolean, won: boolean}} drill
 */
function ghostWords(drill) {
  if (drill.won) return `You beat the ghost: all ${drill.score} balls pocketed!`;
  if (drill.done) return `The ghost wins the rack: ${drill.score} of 9 pocketed. Another rack: Rerack.`;
  return `Ghost 9-ball: hit the lowest ball first and pocket a ball every shot; a miss gives the ghost the rack. Pocketed: ${drill.score} of 9.`;
}

/**
 * The progressive line-up's words: the rule, the rack's balls, the run's score and the
 * table's best.
 * @param {{score: number, done: boolean, won: boolean, balls?: number | null, best?: number}} drill
 */
function lineupWords(drill) {
  const best = drill.best ? ` Best here: ${drill.best}.` : '';
  if (drill.won) return `Line-up cleared to the last rack: ${drill.score} balls pocketed!${best}`;
  if (drill.done) return `Run over: ${drill.score} balls pocketed.${best} Another run: Rerack.`;
  return `Line-up: clear the ${drill.balls} balls in any order, each rack one more; a miss ends the run. Pocketed: ${drill.score}.${best}`;
}

/**
 * The ways on from a finished game, next to Rematch: its analysis (not for practice), a new
 * opponent by Play now (the same game when it is ranked, else 8-ball), and the lobby.
 * @param {import('./state.js').RoomState} state
 */
function renderWaysOn(state) {
  const ended = state.phase === 'over' || Boolean(state.room?.abandoned);
  const ranked = ['nine_ball', 'snooker', 'three_cushion'];
  const game = ranked.includes(state.room?.game ?? '') ? state.room?.game : 'eight_ball';
  const again = /** @type {HTMLAnchorElement} */ ($('new-opponent'));
  const href = `/?playnow=${game}`;
  if (again.getAttribute('href') !== href) again.setAttribute('href', href);
  setHidden(again, !ended);
  setHidden($('end-lobby'), !ended);
  const played = state.phase === 'over' && !state.room?.abandoned;
  setHidden($('analyse'), !(played && state.room?.game !== 'practice'));
}

/**
 * The pocketed balls, per player once the groups are decided (8-ball), the 8 apart.
 * @param {import('./state.js').RoomState} state
 */
export function renderTray(state) {
  const el = $('pocketed');
  const down = pocketedBalls(state);
  const groups = [0, 1].map((seat) => groupOf(state, seat));
  /** @type {{label: string, seat: string, ids: number[]}[]} */
  const rows = [];
  if (groups[0] || groups[1]) {
    for (const seat of [0, 1]) {
      const mine = groupBalls(groups[seat]);
      rows.push({ label: `${playerName(state, seat) ?? `Player ${seat + 1}`} · ${groups[seat]}`,
        seat: String(seat), ids: down.filter((id) => mine.includes(id)) });
    }
    if (down.includes(8)) rows.push({ label: 'The 8', seat: '', ids: [8] });
  } else if (down.length) {
    rows.push({ label: '', seat: '', ids: down });
  }
  const key = JSON.stringify(rows);
  if (el.dataset.key === key) return;
  el.dataset.key = key;
  el.replaceChildren(...rows.map((r) => {
    const row = document.createElement('div');
    row.className = 'tray-row';
    if (r.seat) row.dataset.seat = r.seat;
    if (r.label) {
      const label = document.createElement('span');
      label.className = 'tray-label';
      label.textContent = r.label;
      row.append(label);
    }
    const balls = document.createElement('span');
    balls.className = 'tray-balls';
    balls.replaceChildren(...r.ids.map(miniBall));
    row.append(balls);
    return row;
  }));
}

/**
 * A banner while a player is away: who, and the seconds left before they forfeit the frame.
 * @param {import('./state.js').RoomState} state
 * @param {number} now
 * @param {number} graceAt local time the `grace` list came
 */
export function renderAway(state, now, graceAt) {
  const el = $('away');
  const running = state.room?.abandoned || state.phase === 'over' ? [] : state.grace ?? [];
  const lines = running.filter((g) => g.seat !== state.me.seat || state.me.role !== 'player')
    .map((g) => {
      const name = playerName(state, g.seat) ?? `Player ${g.seat + 1}`;
      const left = countdown(g.remaining - (now - graceAt));
      // Only a player who was here can have left (an older server sends no `left`).
      return g.left === false
        ? `Waiting for ${name} to come to the table · ${left} before forfeiting the frame`
        : `${name} left the table · ${left} to come back before forfeiting the frame`;
    });
  const text = lines.join('\n');
  setText(el, text);
  setHidden(el, !text);
}

/**
 * The decision buttons (e.g. 9-ball push-out answer), shown to the seat that decides, with
 * the question; the others read who is choosing.
 * @param {import('./state.js').RoomState} state
 * @param {(option: string) => void} onDecide
 */
export function renderDecision(state, onDecide) {
  const el = $('decision');
  const d = state.match?.decision;
  const mine = d && state.me.role === 'player' && d.seat === state.me.seat
    && state.phase === 'aiming';
  const key = mine ? JSON.stringify(d) : '';
  if (el.dataset.key === key) return;
  el.dataset.key = key;
  if (!mine) { el.replaceChildren(); return; }
  const prompt = document.createElement('div');
  prompt.className = 'prompt';
  prompt.textContent = d.prompt ?? 'Your choice:';
  el.replaceChildren(prompt, ...d.options.map((/** @type {string} */ opt, /** @type {number} */ i) => {
    const b = document.createElement('button');
    b.textContent = decisionLabel(opt);
    b.dataset.option = opt;
    if (i === 0) b.className = 'primary';
    b.addEventListener('click', () => onDecide(opt));
    return b;
  }));
}

/** @param {import('./state.js').RoomState} state */
export function renderChat(state) {
  const log = $('chat-log');
  if (log.dataset.count === String(state.chat.length)) return;
  log.dataset.count = String(state.chat.length);
  log.replaceChildren(...state.chat.map((c) => {
    const li = document.createElement('li');
    const b = document.createElement('b');
    b.textContent = `${c.name ?? 'spectator'}: `;
    li.append(b, document.createTextNode(c.text));
    return li;
  }));
  log.scrollTop = log.scrollHeight;
}
