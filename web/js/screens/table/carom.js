/**
 * Three-cushion at the live table: the game's scoreboard (points, innings, average, high
 * run, the run and the race) and the count of cushions the striker's cue ball has met as
 * the shot plays. Reads the state's `carom` (the server sends it for three-cushion only).
 */

import { CAROM_NAMES } from '../../balls.js';
import { playerName } from '../../state.js';

/**
 * @typedef {object} CaromScore
 * @property {number[]} points
 * @property {number[]} innings
 * @property {number[]} average
 * @property {number[]} high_run
 * @property {number} run
 * @property {number} race_to
 * @property {boolean} last_inning
 * @property {number[]} cue_balls the ball each seat strikes (0 white, 1 yellow)
 * @property {boolean} opening
 */

/**
 * The ball the striker strikes now: the seat's cue ball in three-cushion, else 0.
 * @param {import('../../state.js').RoomState} state
 * @returns {number}
 */
export function strikerBall(state) {
  const m = /** @type {any} */ (state.match);
  const c = /** @type {CaromScore | undefined} */ (m?.carom);
  return c?.cue_balls?.[m?.turn ?? 0] ?? 0;
}

/**
 * The scoreboard's lines: one per player, then the race and the run.
 * @param {CaromScore} c
 * @param {string[]} names by seat
 * @param {number} turn the seat at the table
 * @returns {string[]}
 */
export function caromLines(c, names, turn) {
  const lines = names.map((name, seat) => {
    const ball = CAROM_NAMES[c.cue_balls[seat] ?? seat] ?? '';
    return `${name} (${ball}): ${c.points[seat] ?? 0} · innings ${c.innings[seat] ?? 0}`
      + ` · average ${(c.average[seat] ?? 0).toFixed(3)} · high run ${c.high_run[seat] ?? 0}`;
  });
  const last = c.last_inning ? ' · last inning' : '';
  const opening = c.opening ? ' · opening: hit the red first' : '';
  lines.push(`Race to ${c.race_to} · run ${c.run} (${names[turn] ?? ''})${last}${opening}`);
  return lines;
}

/** Counts the cushions a ball meets, from its drawn positions, frame by frame. */
export class CushionCounter {
  constructor() {
    this.count = 0;
    this.near = false;
  }

  /** Start again for a new shot. */
  reset() {
    this.count = 0;
    this.near = true; // a ball at rest against a cushion has not met it yet
  }

  /**
   * The ball's centre now: a cushion met when it comes within a hair of a rail's line.
   * @param {{length: number, width: number, ball_radius: number}} table
   * @param {number} x
   * @param {number} y
   */
  update(table, x, y) {
    const r = table.ball_radius;
    const gap = Math.min(x, y, table.length - x, table.width - y) - r;
    const near = gap < 0.004;
    if (near && !this.near) this.count += 1;
    this.near = near;
  }
}

/**
 * Show the scoreboard and the cushions counted.
 * @param {import('../../state.js').RoomState} state
 * @param {CushionCounter} counter
 */
export function renderCarom(state, counter) {
  const box = document.getElementById('carom-box');
  const el = document.getElementById('carom');
  const count = document.getElementById('cushions');
  const m = /** @type {any} */ (state.match);
  const c = /** @type {CaromScore | undefined} */ (m?.carom);
  if (!box || !el || !count) return;
  box.hidden = !c;
  if (!c) return;
  const names = [0, 1].map((s) => playerName(state, s) ?? m?.players?.[s] ?? `Player ${s + 1}`);
  const text = caromLines(c, names, m?.turn ?? 0).join('\n');
  if (el.textContent !== text) el.textContent = text;
  const shown = `Cushions: ${counter.count}`;
  if (count.textContent !== shown) count.textContent = shown;
}
