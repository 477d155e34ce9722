/**
 * Play now, in the lobby: choose 8-ball or 9-ball and press Play now. The server pairs
 * waiting players by rating (the client never decides who joins whom); this screen only
 * long-polls `GET /api/playnow` until it is told the room and seat, then goes there. After
 * a while alone it offers the computer at the level nearest the player's rating.
 */

import { api, memory } from '../net.js';
import { players, RANKED_GAMES, gameName } from '../players.js';
import { onName, profileName } from '../identity.js';

const POLL_WAIT = 25; // s the server may hold a long-poll
const RETRY_AFTER = 2000; // ms before polling again after a failed request

/**
 * @param {string} tag
 * @param {Record<string, string>} [attrs]
 * @param {string} [text]
 */
function el(tag, attrs = {}, text = '') {
  const node = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) node.setAttribute(k, v);
  if (text) node.textContent = text;
  return node;
}

/**
 * Build the Play now panel inside `root`.
 * @param {HTMLElement} root
 * @param {() => Promise<string>} settleName the name to play under, saved to the profile
 *   first (throws one sentence when it is refused)
 * @param {string | null} [again] a game to queue for at once ("New opponent" after a game)
 */
export function mountPlayNow(root, settleName, again = null) {
  const game = /** @type {HTMLSelectElement} */ (el('select', { 'data-testid': 'playnow-game' }));
  for (const [value, label] of RANKED_GAMES) game.append(el('option', { value }, label));
  const label = el('label', { class: 'field' }, 'Game');
  label.append(game);
  const play = el('button', { class: 'primary', 'data-testid': 'play-now' }, 'Play now');
  const cancel = el('button', { 'data-testid': 'playnow-cancel', hidden: '' }, 'Stop looking');
  const computer = el('button', { 'data-testid': 'playnow-computer', hidden: '' });
  const row = el('div', { class: 'row' });
  row.append(label, play, cancel, computer);
  const status = el('p', { class: 'muted', 'data-testid': 'playnow-status', 'aria-live': 'polite' });
  const links = el('p', { class: 'small' });
  const who = el('span', { 'data-testid': 'playnow-name' });
  links.append(who,
    el('a', { href: '/profile', 'data-testid': 'profile-link' }, 'Your profile'), ' · ',
    el('a', { href: '/leaderboard', 'data-testid': 'leaderboard-link' }, 'Leaderboard'), ' · ',
    el('a', { href: '/login', 'data-testid': 'login-link' }, 'Sign in'));
  root.replaceChildren(el('h2', {}, 'Play now'),
    el('p', { class: 'muted small' },
      'A ranked game with someone of your strength, in seconds.'), row, status, links);

  let name = '';

  let polling = false;
  /** @type {ReturnType<typeof setInterval> | undefined} */
  let ticking;
  /** @param {any} s a PlayNowStatus */
  const show = (s) => {
    clearInterval(ticking);
    const waiting = s.status === 'waiting';
    play.hidden = waiting;
    cancel.hidden = !waiting;
    computer.hidden = !(waiting && s.computer);
    if (s.status === 'matched' && s.room) {
      status.textContent = `Opponent found: ${s.room.opponent}. Going to the table…`;
      memory.setSeat(s.room.room_id, { seat: s.room.seat, token: s.room.token, name });
      location.assign(s.room.url);
      return false;
    }
    if (waiting) {
      // The wait counts up here between two answers of the long-poll.
      const since = performance.now() - s.waited * 1000;
      const tell = () => {
        const game = gameName(s.game);
        status.textContent = `Looking for ${game.startsWith('8') ? 'an' : 'a'} ${game} opponent rated `
          + `${Math.round(s.rating)} ± ${Math.round(s.window)}… `
          + `(${Math.round((performance.now() - since) / 1000)} s)`;
      };
      tell();
      ticking = setInterval(tell, 1000);
      if (s.computer) computer.textContent = `Play the computer (${s.computer}) instead`;
      return true;
    }
    status.textContent = '';
    return false;
  };
  const poll = async () => {
    if (polling) return;
    polling = true;
    try {
      for (;;) {
        let s;
        try { s = await players.queueStatus(POLL_WAIT); } catch {
          await new Promise((r) => setTimeout(r, RETRY_AFTER));
          continue;
        }
        if (!show(s)) break;
      }
    } finally { polling = false; }
  };
  /** @param {unknown} e */
  const fail = (e) => { status.textContent = e instanceof Error ? e.message : String(e); };

  const playNow = async () => {
    try {
      await settleName();
      if (show(await players.playNow(game.value))) poll();
    } catch (e) { fail(e); }
  };
  play.addEventListener('click', playNow);
  cancel.addEventListener('click', async () => {
    try { show(await players.leaveQueue()); } catch (e) { fail(e); }
  });
  computer.addEventListener('click', async () => {
    try { show(await players.playComputer()); } catch (e) { fail(e); }
  });
  onName((n) => {
    name = n;
    who.textContent = `Playing as ${name} · `;
  });
  // The profile first (a first visit makes it and its cookie); then, back in the lobby
  // while still queued (another tab, a reload), pick the wait up again, or go to a match
  // still on. A finished match is never gone back to: the lobby stays the lobby.
  profileName().then(async () => {
    if (again && RANKED_GAMES.some(([g]) => g === again)) {
      game.value = again;
      history.replaceState(null, '', '/');
      await playNow();
      return;
    }
    const s = await players.queueStatus(0);
    if (s.status === 'matched' && !(await stillOn(s.room?.room_id))) return;
    if (show(s)) poll();
  }).catch(() => { status.textContent = 'Your profile could not be loaded.'; });
}

/**
 * Whether a Play now room is still to be played (not finished, not gone).
 * @param {string | undefined} roomId
 */
async function stillOn(roomId) {
  if (!roomId) return false;
  try {
    const room = await api.getRoom(roomId);
    return room.status !== 'finished';
  } catch { return false; }
}
