/**
 * Joining a seat or watching: a visitor without a seat at a table with a free one is asked
 * to join or watch (under the profile's name, prefilled); `?watch` in the address only watches. The socket watches while the
 * visitor decides and reconnects with the seat's token once seated.
 */

import { api, memory } from '../../net.js';
import { isPractice } from '../../balls.js';
import { $, $input } from '../../ui.js';
import { bindNameField, profileName, settleName } from '../../identity.js';

/** @type {Record<string, string>} */
const GAME_NAMES = {
  eight_ball: '8-ball', nine_ball: '9-ball', practice: 'Practice', snooker: 'Snooker',
  snooker_practice: 'Snooker practice',
  three_cushion_practice: 'Three-cushion practice',
  three_cushion: 'Three-cushion',
};

/**
 * @param {string} roomId
 * @param {any} room `GET /api/rooms/{room_id}` (null when it could not be read)
 * @param {import('../../net.js').RoomSocket} socket
 */
export function chooseSeat(roomId, room, socket) {
  socket.connect(); // watch while deciding
  if (memory.seat(roomId)?.token || !room) return;
  const watchOnly = new URLSearchParams(location.search).has('watch');
  /** @type {(string | null)[]} */
  const players = room.players ?? [];
  const free = players.some((p) => p === null);
  if (!free || watchOnly) return;
  const dialog = $('join-dialog');
  const nameEl = $input('join-name');
  bindNameField(nameEl); // the profile's name; a new one typed here renames the profile
  $('join-info').textContent = invitation(room, players.filter(Boolean));
  // Joining a ranked table is the player's agreement to be rated.
  $('join-seat').textContent = room.ranked ? 'Join the ranked game' : 'Join the game';
  dialog.hidden = false;
  $('watch-only').onclick = () => { dialog.hidden = true; };
  $('join-seat').onclick = async () => {
    try {
      const name = await settleName(nameEl);
      // A ranked seat needs a profile: made here when the link is the first visit.
      if (room?.ranked) await profileName();
      const seat = await api.join(roomId, name, Boolean(room?.ranked));
      memory.setSeat(roomId, { seat: seat.seat, token: seat.token, name: seat.name });
      dialog.hidden = true;
      socket.reconnect();
    } catch (e) { $('join-error').textContent = e instanceof Error ? e.message : String(e); }
  };
}

/**
 * The dialog's words: the game, who waits, whether it is ranked.
 * @param {any} room
 * @param {(string | null)[]} names the seated players
 */
export function invitation(room, names) {
  const game = GAME_NAMES[room.game] ?? room.game;
  const what = isPractice(room.game) ? 'A practice table.'
    : `${game} · race to ${room.race_to}`
      + (room.shot_clock > 0 ? ` · ${Math.round(room.shot_clock)} s shot clock.` : '.');
  const who = names.length
    ? `${names.join(' and ')} ${names.length > 1 ? 'are' : 'is'} waiting for an opponent.`
    : 'This table has a free seat.';
  return `${what} ${who}${room.ranked ? ' This table is ranked: your rating will change.' : ''}`;
}
