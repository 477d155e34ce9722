/**
 * The leaderboard (`/leaderboard?game=eight_ball|nine_ball`): rank, name, rating shown as
 * rating − 2·RD (the rating the player is very likely above), games; provisional players
 * listed after them, their rating marked "?" and explained, without a rank.
 */

import { players, RANKED_GAMES, gameName } from '../players.js';

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
 * @param {any[]} rows standings
 * @param {string} testid
 * @param {boolean} [provisional] marked "?" (no rank yet)
 */
function standingsTable(rows, testid, provisional = false) {
  const table = el('table', { class: 'standings', 'data-testid': testid });
  const header = el('tr');
  for (const h of ['#', 'Player', 'Rating', 'Games']) header.append(el('th', {}, h));
  table.append(header);
  for (const row of rows) {
    const tr = el('tr', { 'data-testid': 'standing' });
    const who = el('td');
    who.append(el('a', { href: `/p/${encodeURIComponent(row.player_id)}`,
      'data-testid': 'standing-name' }, row.name));
    tr.append(el('td', {}, row.rank === null ? '–' : String(row.rank)), who,
      el('td', { 'data-testid': 'standing-rating',
        ...(provisional ? { title: 'Provisional: too few recent ranked games to rank' } : {}) },
      `${Math.round(row.rating)}${provisional ? '?' : ''}`),
      el('td', {}, String(row.games)));
    table.append(tr);
  }
  return table;
}

export async function startLeaderboard() {
  const root = /** @type {HTMLElement} */ (document.getElementById('leaderboard'));
  root.hidden = false;
  document.title = 'Pool online · leaderboard';
  const asked = new URLSearchParams(location.search).get('game');
  const game = RANKED_GAMES.some(([g]) => g === asked) ? /** @type {string} */ (asked)
    : 'eight_ball';
  const nav = el('p', { class: 'small' });
  nav.append(el('a', { href: '/' }, '← Lobby'));
  for (const [g, label] of RANKED_GAMES) {
    nav.append(' · ');
    nav.append(g === game ? el('strong', {}, label)
      : el('a', { href: `/leaderboard?game=${g}`, 'data-testid': `leaderboard-${g}` }, label));
  }
  const panel = el('section', { class: 'panel' });
  panel.append(el('h1', {}, `${gameName(game)} leaderboard`),
    el('p', { class: 'muted small' },
      'Rating shown as rating − 2 × deviation: a new or long-absent player climbs by playing.'));
  root.replaceChildren(nav, panel);
  try {
    const board = await players.leaderboard(game);
    const ranked = board.ranked.length, waiting = board.provisional.length;
    if (ranked) panel.append(standingsTable(board.ranked, 'leaderboard-ranked'));
    else {
      panel.append(el('p', { class: 'muted', 'data-testid': 'leaderboard-ranked' }, waiting
        ? 'No rank yet for anyone: every player so far is provisional (below).'
        : 'Nobody has played a ranked game yet: press Play now in the lobby.'));
    }
    const apart = el('section', { class: 'panel' });
    apart.append(el('h2', {}, `Provisional (${waiting})`),
      el('p', { class: 'muted small', 'data-testid': 'provisional-why' },
        'A rating marked ? is provisional: its deviation is still above 110, after too few'
        + ' recent ranked games (or a long absence). It gets a rank after a few more games.'),
      standingsTable(board.provisional, 'leaderboard-provisional', true));
    root.append(apart);
  } catch (e) {
    panel.append(el('p', { class: 'error', role: 'alert' },
      e instanceof Error ? e.message : String(e)));
  }
}
