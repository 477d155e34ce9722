/**
 * The lobby (`/`): three equal ways to play (Play now, the computer, a friend by link) and
 * practice, the open tables to join or watch and the finished matches to watch again.
 * Everyone plays under their profile's name (identity.js): the name field is prefilled
 * with it and a new name typed there renames the profile. Lists refresh every few seconds
 * while the tab is shown.
 */

import { api, memory, request } from '../net.js';
import { DEFAULT_LIMITS, readLimits } from '../limits.js';
import { $, $input, $select, applyInputLimits, renderRooms, renderHistory } from '../ui.js';
import { mountPlayNow } from './playnow.js';
import { isPractice } from '../balls.js';
import { bindNameField, settleName } from '../identity.js';

const REFRESH_EVERY = 3000; // ms between two refreshes of the lists
const HISTORY_SHOWN = 10; // finished matches listed

export function startLobby() {
  $('lobby').hidden = false;
  // The name field's length follows the server's limit: the defaults until it answers.
  applyInputLimits(DEFAULT_LIMITS);
  api.limits().then((limits) => applyInputLimits(readLimits(limits)), () => {});
  // The computer's levels, as the server names them (weakest first).
  api.computerLevels().then(({ levels }) => {
    const select = $select('computer-level');
    for (const level of levels) {
      const option = document.createElement('option');
      option.value = level;
      option.textContent = level[0].toUpperCase() + level.slice(1);
      select.append(option);
    }
  }, () => {});

  const nameEl = $input('name');
  bindNameField(nameEl, true); // saved to the profile as typed
  // `/?playnow=<game>`: "New opponent" at the end of a game queues at once.
  const again = new URLSearchParams(location.search).get('playnow');
  mountPlayNow($('playnow'), () => settleName(nameEl), again);
  /** @param {string} msg */
  const showError = (msg) => { $('lobby-error').textContent = msg; };
  // Practice is one rack alone: no race, no clock to set.
  const gameEl = $select('game');
  const showGameOptions = () => {
    const practice = isPractice(gameEl.value);
    $input('race-to').disabled = practice;
    $select('shot-clock-select').disabled = practice;
    // Ranked: two people at 8-ball or 9-ball (never practice).
    $input('ranked-table').disabled = practice;
  };
  gameEl.addEventListener('change', showGameOptions);
  showGameOptions();
  /** The name to play under (the profile's, renamed first when changed here), or null. */
  const needName = async () => {
    try { return await settleName(nameEl); } catch (e) {
      showError(errorText(e));
      nameEl.focus();
      return null;
    }
  };
  /**
   * @param {string} roomId
   * @param {string} name
   * @param {boolean} [ranked] the creator's agreement to their own ranked table
   */
  const joinAndGo = async (roomId, name, ranked = false) => {
    const seat = await api.join(roomId, name, ranked);
    memory.setSeat(roomId, { seat: seat.seat, token: seat.token, name: seat.name });
    location.assign(`/r/${roomId}`);
  };
  /**
   * Open a table and take its first seat.
   * @param {{game: string, raceTo: number, shotClock?: number, listed: boolean,
   *   opponent?: string, ranked?: boolean}} t
   */
  const openTable = async (t) => {
    const name = await needName();
    if (!name) return;
    try {
      const room = await api.createRoom(t.game, t.raceTo, t.shotClock, t.listed, t.opponent,
        t.ranked);
      await joinAndGo(room.room_id, name, t.ranked);
    } catch (e) { showError(errorText(e)); }
  };
  $('create-room').addEventListener('click', () => {
    // Kept within the field's own min/max (index.html), which is what the form offers.
    const raceEl = $input('race-to');
    const lo = Number(raceEl.min) || 1;
    const raceTo = Math.min(Number(raceEl.max) || lo, Math.max(lo, Number(raceEl.value) || lo));
    const practice = isPractice($select('game').value);
    const shotClock = practice ? undefined : Number($select('shot-clock-select').value);
    openTable({ game: $select('game').value, raceTo: practice ? 1 : raceTo,
      shotClock: Number.isFinite(shotClock) ? shotClock : undefined,
      listed: !$input('private-table').checked,
      ranked: !$input('ranked-table').disabled && $input('ranked-table').checked });
  });
  // A game against the computer is nobody else's to join: kept out of the lobby.
  $('play-computer').addEventListener('click', () => openTable({
    game: $select('computer-game').value, raceTo: Number($select('computer-race-to').value),
    shotClock: Number($select('computer-clock').value), listed: false,
    opponent: $select('computer-level').value || 'beginner' }));
  $('practice').addEventListener('click', () => openTable({ game: 'practice', raceTo: 1,
    listed: true }));
  const refresh = async () => {
    try {
      const { rooms } = await api.listRooms();
      /** @type {any[]} */
      const all = rooms;
      // A finished table is nobody's to join: only tables waiting or in play are open.
      const open = all.filter((r) => r.status !== 'finished');
      renderRooms($('rooms'), open, {
        onJoin: async (id) => {
          // A ranked table asks for the player's agreement: its page's join dialog does.
          if (open.some((r) => r.room_id === id && r.ranked)) { location.assign(`/r/${id}`); return; }
          const name = await needName();
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
      const matches = await endedMatches(HISTORY_SHOWN);
      renderHistory($('history'), matches);
      $('no-history').hidden = matches.length > 0;
    } catch (e) { showError(`Cannot list finished matches: ${errorText(e)}`); }
  };
  refresh();
  refreshHistory();
  setInterval(() => { if (!document.hidden) { refresh(); refreshHistory(); } }, REFRESH_EVERY);
}

/**
 * The newest matches that ended: finished ones with at least one shot to watch, and the
 * abandoned ones (said so, never as a win), newest first.
 * @param {number} limit
 * @returns {Promise<any[]>}
 */
async function endedMatches(limit) {
  const [finished, abandoned] = await Promise.all(['finished', 'abandoned'].map((status) =>
    request('GET', `/api/matches?status=${status}&limit=${limit}`)));
  /** @type {any[]} */
  const all = [...finished.matches.filter((/** @type {any} */ m) => m.shots > 0),
    ...abandoned.matches];
  const when = (/** @type {any} */ m) => m.finished_at ?? m.started_at ?? 0;
  return all.sort((a, b) => when(b) - when(a)).slice(0, limit);
}

/** @param {unknown} e */
function errorText(e) {
  return e instanceof Error ? e.message : String(e);
}
