/**
 * The lobby (`/`): your name, creating a table, the open tables to join or watch and the
 * finished matches to watch again. Lists refresh every few seconds while the tab is shown.
 */

import { api, memory } from '../net.js';
import { DEFAULT_LIMITS, readLimits } from '../limits.js';
import { $, $input, $select, applyInputLimits, renderRooms, renderHistory } from '../ui.js';

const REFRESH_EVERY = 3000; // ms between two refreshes of the lists
const HISTORY_SHOWN = 10; // finished matches listed

export function startLobby() {
  $('lobby').hidden = false;
  // The name field's length follows the server's limit: the defaults until it answers.
  applyInputLimits(DEFAULT_LIMITS);
  api.limits().then((limits) => applyInputLimits(readLimits(limits)), () => {});
  // The computer's levels, as the server names them (weakest first).
  api.computerLevels().then(({ levels }) => {
    const select = $select('opponent');
    for (const level of levels) {
      const option = document.createElement('option');
      option.value = level;
      option.textContent = `The computer: ${level}`;
      select.append(option);
    }
  }, () => {});

  const nameEl = $input('name');
  nameEl.value = memory.name();
  nameEl.addEventListener('input', () => memory.setName(nameEl.value.trim()));
  /** @param {string} msg */
  const showError = (msg) => { $('lobby-error').textContent = msg; };
  const needName = () => {
    const name = nameEl.value.trim();
    if (!name) { showError('Enter your name first.'); nameEl.focus(); return null; }
    memory.setName(name);
    return name;
  };
  /**
   * @param {string} roomId
   * @param {string} name
   */
  const joinAndGo = async (roomId, name) => {
    const seat = await api.join(roomId, name);
    memory.setSeat(roomId, { seat: seat.seat, token: seat.token, name: seat.name });
    location.assign(`/r/${roomId}`);
  };
  $('create-room').addEventListener('click', async () => {
    const name = needName();
    if (!name) return;
    // Kept within the field's own min/max (index.html), which is what the form offers.
    const raceEl = $input('race-to');
    const lo = Number(raceEl.min) || 1;
    const raceTo = Math.min(Number(raceEl.max) || lo, Math.max(lo, Number(raceEl.value) || lo));
    try {
      const opponent = $select('opponent').value || undefined;
      // A game against the computer is nobody else's to join: keep it out of the lobby.
      const listed = !$input('private-table').checked && !opponent;
      const room = await api.createRoom($select('game').value, raceTo, undefined, listed,
        opponent);
      await joinAndGo(room.room_id, name);
    } catch (e) { showError(errorText(e)); }
  });
  const refresh = async () => {
    try {
      const { rooms } = await api.listRooms();
      /** @type {any[]} */
      const all = rooms;
      const open = all.filter((r) => r.status !== 'finished' || r.spectators > 0);
      renderRooms($('rooms'), open, {
        onJoin: async (id) => {
          const name = needName();
          if (!name) return;
          try { await joinAndGo(id, name); } catch (e) { showError(errorText(e)); refresh(); }
        },
        onWatch: (id) => location.assign(`/r/${id}?watch=1`),
      });
      $('no-rooms').hidden = open.length > 0;
    } catch (e) { showError(`Cannot list tables: ${errorText(e)}`); }
  };
  const refreshHistory = async () => {
    try {
      const { matches } = await api.finishedMatches(HISTORY_SHOWN);
      renderHistory($('history'), matches);
      $('no-history').hidden = matches.length > 0;
    } catch (e) { showError(`Cannot list finished matches: ${errorText(e)}`); }
  };
  refresh();
  refreshHistory();
  setInterval(() => { if (!document.hidden) { refresh(); refreshHistory(); } }, REFRESH_EVERY);
}

/** @param {unknown} e */
function errorText(e) {
  return e instanceof Error ? e.message : String(e);
}
