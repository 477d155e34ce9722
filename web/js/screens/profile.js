/**
 * A player's profile: `/profile` (your own: the name can be changed, and is
 * used at every table from then on; the account part, screens/account.js) or `/p/{player_id}`
 * (anyone's). Ratings per game (provisional ones marked), the recent ranked matches with
 * their rating change, and every recent match in the player's seats, each with a link to
 * its replay. Every name is written as text, never as markup.
 */

import { players, RANKED_GAMES, gameName, ratingText } from '../players.js';
import { bindNameField, myProfile, settleName } from '../identity.js';
import { accountPanel } from './account.js';

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

/** @param {string | null} playerId null: the asking player's own profile */
export async function startProfile(playerId) {
  const root = /** @type {HTMLElement} */ (document.getElementById('profile'));
  root.hidden = false;
  document.title = 'Pool online · profile';
  const error = el('p', { class: 'error', role: 'alert', 'data-testid': 'profile-error' });
  let profile;
  try {
    profile = playerId === null ? await myProfile() : await players.get(playerId);
  } catch (e) {
    root.replaceChildren(el('a', { href: '/' }, '← Lobby'), error);
    error.textContent = e instanceof Error ? e.message : String(e);
    return;
  }
  const nav = el('p', { class: 'small' });
  nav.append(el('a', { href: '/' }, '← Lobby'), ' · ',
    el('a', { href: '/leaderboard' }, 'Leaderboard'));
  if (profile.me && !profile.account) {
    nav.append(' · ', el('a', { href: '/login', 'data-testid': 'profile-login' },
      'Sign in to another player'));
  }
  root.replaceChildren(nav, headPanel(profile, error), ratingsPanel(profile),
    recentPanel(profile.recent), matchesPanel(profile.matches));
  if (profile.me) root.insertBefore(accountPanel(profile), root.children[2]);
}

/**
 * The name (with the rename field on your own profile) and the error line.
 * @param {any} profile
 * @param {HTMLElement} error
 */
function headPanel(profile, error) {
  const title = el('h1', { 'data-testid': 'profile-name' }, profile.name);
  const head = el('section', { class: 'panel' });
  head.append(title);
  if (profile.me) {
    const input = /** @type {HTMLInputElement} */ (el('input', {
      'data-testid': 'profile-name-input', 'data-limit': 'max_name', maxlength: '24',
      autocomplete: 'nickname' }));
    input.value = profile.name;
    const save = el('button', { class: 'primary', 'data-testid': 'profile-save' }, 'Save name');
    const field = el('label', { class: 'field' }, 'Your name');
    field.append(input);
    const row = el('div', { class: 'row' });
    row.append(field, save);
    head.append(row);
    bindNameField(input); // its limit shown while typing, a cut paste said
    save.addEventListener('click', async () => {
      try {
        const name = await settleName(input);
        title.textContent = name;
        input.value = name;
        error.textContent = '';
      } catch (e) { error.textContent = e instanceof Error ? e.message : String(e); }
    });
  }
  head.append(error);
  return head;
}

/**
 * The rating per ranked game played.
 * @param {any} profile
 */
function ratingsPanel(profile) {
  const ratings = el('section', { class: 'panel' });
  ratings.append(el('h2', {}, 'Ratings'));
  const table = el('table', { class: 'standings', 'data-testid': 'profile-ratings' });
  const header = el('tr');
  for (const h of ['Game', 'Rating', 'Deviation', 'Games', 'Wins']) header.append(el('th', {}, h));
  table.append(header);
  for (const [game] of RANKED_GAMES) {
    const r = profile.ratings.find((/** @type {any} */ x) => x.game === game);
    if (!r) continue;
    const tr = el('tr', { 'data-testid': `rating-${game}` });
    tr.append(el('td', {}, gameName(game)), el('td', { 'data-testid': 'rating' }, ratingText(r)),
      el('td', {}, `±${Math.round(r.rd)}`), el('td', {}, String(r.games)),
      el('td', {}, String(r.wins)));
    table.append(tr);
  }
  ratings.append(table, el('p', { class: 'muted small' },
    'A rating marked ? is provisional: too few recent ranked games to be sure.'));
  return ratings;
}

/**
 * The recent ranked matches with the rating change of each.
 * @param {any[]} matches
 */
function recentPanel(matches) {
  const recent = el('section', { class: 'panel' });
  recent.append(el('h2', {}, 'Recent ranked matches'));
  const list = el('ul', { class: 'rooms', 'data-testid': 'profile-recent' });
  for (const m of matches) {
    const li = el('li', { 'data-testid': 'recent-match' });
    const what = el('div', { class: 'what' });
    const change = m.rating_after !== null && m.rating_before !== null
      ? ` (${m.rating_after >= m.rating_before ? '+' : ''}`
        + `${Math.round(m.rating_after - m.rating_before)})` : '';
    what.append(el('div', {}, `${m.won ? 'Won' : 'Lost'} against ${m.opponent}${change}`),
      el('div', { class: 'who' }, [gameName(m.game),
        m.finished_at ? new Date(m.finished_at * 1000).toLocaleString() : ''].filter(Boolean)
        .join(' · ')));
    li.append(what);
    if (m.replay) li.append(el('a', { class: 'button', href: m.replay,
      'data-testid': 'recent-replay' }, 'Watch'));
    list.append(li);
  }
  recent.append(list);
  if (!matches.length) recent.append(el('p', { class: 'muted' }, 'No ranked match yet.'));
  return recent;
}

/**
 * Every recent match in the player's seats.
 * @param {any[]} matches
 */
function matchesPanel(matches) {
  const played = el('section', { class: 'panel' });
  played.append(el('h2', {}, 'Matches'));
  const games = el('ul', { class: 'rooms', 'data-testid': 'profile-matches' });
  for (const m of matches) {
    const li = el('li', { 'data-testid': 'played-match' });
    const what = el('div', { class: 'what' });
    const result = m.won === null ? (m.status === 'abandoned' ? 'Abandoned' : 'In play')
      : m.won ? 'Won' : 'Lost';
    what.append(el('div', {}, `${result}: ${m.players.join(' vs ')} (${m.score.join('–')})`),
      el('div', { class: 'who' }, [gameName(m.game),
        new Date((m.finished_at ?? m.started_at) * 1000).toLocaleString()].join(' · ')));
    li.append(what);
    if (m.replay) li.append(el('a', { class: 'button', href: m.replay,
      'data-testid': 'match-replay' }, 'Watch'));
    games.append(li);
  }
  played.append(games);
  if (!matches.length) played.append(el('p', { class: 'muted' }, 'No match yet.'));
  return played;
}
