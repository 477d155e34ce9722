/**
 * The players' HTTP API (docs/protocol.md, "Players, Play now and the leaderboard"): the
 * profile the server makes on a first visit (its secret stays in an HttpOnly cookie the
 * page never sees), the leaderboard and the Play now queue.
 */

import { request } from './net.js';

/** The game kinds that are ranked, with the names shown. */
export const RANKED_GAMES = /** @type {const} */ ([
  ['eight_ball', '8-ball'],
  ['nine_ball', '9-ball'],
  ['snooker', 'Snooker'],
  ['three_cushion', 'Three-cushion'],
]);

/** @param {string} game */
export const gameName = (game) => RANKED_GAMES.find(([g]) => g === game)?.[1] ?? game;

export const players = {
  /** The asking player's profile (made, with its cookie, on a first visit). */
  me: () => request('GET', '/api/players/me'),
  /** @param {string} name */
  rename: (name) => request('PATCH', '/api/players/me', { name }),
  /** @param {string} playerId */
  get: (playerId) => request('GET', `/api/players/${encodeURIComponent(playerId)}`),
  /** @param {string} game */
  leaderboard: (game) => request('GET', `/api/leaderboard/${encodeURIComponent(game)}`),
  /** @param {string} game */
  playNow: (game) => request('POST', '/api/playnow', { game }),
  /** @param {number} wait seconds the server may hold the answer until something changes */
  queueStatus: (wait) => request('GET', `/api/playnow?wait=${wait}`),
  leaveQueue: () => request('DELETE', '/api/playnow'),
  playComputer: () => request('POST', '/api/playnow/computer'),
};

/**
 * A rating as shown: the rounded rating, "?" after it while provisional.
 * @param {{rating: number, provisional: boolean}} r
 */
export function ratingText(r) {
  return `${Math.round(r.rating)}${r.provisional ? '?' : ''}`;
}
