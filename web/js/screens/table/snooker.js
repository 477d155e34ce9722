/**
 * Snooker at the live table: the frame's scoreboard (points, the break, the ball on, the
 * points remaining, the snookers required, the frames) and the nomination of a colour or a
 * free ball, by tapping the ball on the table or its button. Reads the state's `frame` and
 * `nominations` (the server sends both for a snooker game only).
 */

import { snookerBallName } from '../../balls.js';
import { dist } from '../../geometry.js';
import { playerName } from '../../state.js';

/**
 * @typedef {object} FrameScore
 * @property {number[]} points
 * @property {number} current_break
 * @property {number[]} highest_break
 * @property {string} on "red", "colour" or a colour's name
 * @property {number | null} nominated
 * @property {boolean} free_ball
 * @property {number} remaining
 * @property {number[]} snookers_required
 */

/**
 * The scoreboard's lines: one per player, then the break and what is on.
 * @param {FrameScore} f
 * @param {string[]} names by seat
 * @param {number[] | undefined} frames frames won by seat
 * @param {number} turn the seat at the table
 * @returns {string[]}
 */
export function frameLines(f, names, frames, turn) {
  const lines = names.map((name, seat) => {
    const won = frames ? ` (${frames[seat] ?? 0})` : '';
    const need = f.snookers_required[seat] ?? 0;
    const snookers = need ? ` · needs ${need} snooker${need > 1 ? 's' : ''}` : '';
    return `${name}${won}: ${f.points[seat] ?? 0}${snookers}`;
  });
  const on = f.on === 'red' ? 'a red' : f.on === 'colour' ? 'a colour' : `the ${f.on}`;
  const nominated = f.nominated != null ? ` · nominated ${snookerBallName(f.nominated)}` : '';
  const free = f.free_ball ? ' · free ball' : '';
  lines.push(`Break ${f.current_break} (${names[turn] ?? ''}) · on ${on}${nominated}${free}`);
  lines.push(`Remaining ${f.remaining}`);
  return lines;
}

/**
 * The nominable ball under a point of the table, else null.
 * @param {{id: number, x: number, y: number}[]} balls
 * @param {number[]} nominations
 * @param {number} radius
 * @param {number} x
 * @param {number} y
 * @returns {number | null}
 */
export function nominationAt(balls, nominations, radius, x, y) {
  for (const b of balls) {
    if (nominations.includes(b.id) && dist(x, y, b.x, b.y) <= radius * 1.3) return b.id;
  }
  return null;
}

/**
 * Show the frame's scoreboard and, to the striker, the balls to nominate.
 * @param {import('../../state.js').RoomState} state
 * @param {(ball: number) => void} onNominate
 */
export function renderFrame(state, onNominate) {
  const box = document.getElementById('frame-box');
  const el = document.getElementById('frame');
  const pick = document.getElementById('nominate');
  const m = /** @type {any} */ (state.match);
  const f = /** @type {FrameScore | undefined} */ (m?.frame);
  if (!box || !el || !pick) return;
  box.hidden = !f;
  if (!f) return;
  const names = [0, 1].map((s) => playerName(state, s) ?? m?.players?.[s] ?? `Player ${s + 1}`);
  const text = frameLines(f, names, m?.score, m?.turn ?? 0).join('\n');
  if (el.textContent !== text) el.textContent = text;
  const mine = state.me.role === 'player' && m?.turn === state.me.seat && state.phase === 'aiming'
    && !m?.decision;
  const choices = mine ? /** @type {number[]} */ (m?.nominations ?? []) : [];
  const key = JSON.stringify([choices, f.nominated]);
  if (pick.dataset.key === key) return;
  pick.dataset.key = key;
  pick.replaceChildren(...choices.map((ball) => {
    const b = document.createElement('button');
    b.textContent = `Nominate ${snookerBallName(ball)}`;
    b.dataset.ball = String(ball);
    if (ball === f.nominated) b.className = 'primary';
    b.addEventListener('click', () => onNominate(ball));
    return b;
  }));
}
