/**
 * A player's profile: `/profile` (your own: the name can be changed, and is
 * used at every table from then on; the account part, screens/account.js) or `/p/{player_id}`
 * (anyone's). Ratings per game (provisional ones marked), the accuracy in the analysed
 * matches (a small chart), the recent ranked matches with
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
    accuracyPanel(profile.matches, profile.drills), recentPanel(profile.recent),
    matchesPanel(profile.matches));
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

const SVG = 'http://www.w3.org/2000/svg';
const CHART_W = 320;
const CHART_H = 80;

/**
 * The player's accuracy (0-100) in their analysed recent matches, oldest to newest, as a
 * small line chart (a match not analysed is left out).
 * With the personal bests of the drills under it.
 * @param {any[]} matches newest first
 * @param {{tries: number, made: number, best_run: number, ghost_racks?: number,
 *   ghost_cleared?: number, ghost_best?: number, lineup_runs?: number,
 *   lineup_best?: number} | null | undefined} drills
 */
function accuracyPanel(matches, drills) {
  const panel = el('section', { class: 'panel' });
  panel.append(el('h2', {}, 'Accuracy and drills'));
  if (drills?.tries) {
    panel.append(el('p', { class: 'small', 'data-testid': 'profile-drills' },
      `Position drills: made ${drills.made} of ${drills.tries}; best run ${drills.best_run} in a row.`));
  }
  if (drills?.ghost_racks) {
    panel.append(el('p', { class: 'small', 'data-testid': 'profile-ghost' },
      `Ghost 9-ball: best ${drills.ghost_best} of 9 pocketed; the ghost beaten ${
        drills.ghost_cleared} of ${drills.ghost_racks} racks.`));
  }
  if (drills?.lineup_runs) {
    panel.append(el('p', { class: 'small', 'data-testid': 'profile-lineup' },
      `Line-up: best run ${drills.lineup_best} balls pocketed, of ${drills.lineup_runs} runs.`));
  }
  const points = matches.filter((m) => typeof m.accuracy === 'number').reverse()
    .map((m) => /** @type {number} */ (m.accuracy));
  if (!points.length) {
    panel.append(el('p', { class: 'muted', 'data-testid': 'accuracy-none' },
      'No analysed match yet: press Analyse after a game, or on its replay.'));
    return panel;
  }
  const chart = document.createElementNS(SVG, 'svg');
  chart.setAttribute('viewBox', `0 0 ${CHART_W} ${CHART_H}`);
  chart.setAttribute('class', 'accuracy-chart');
  chart.setAttribute('data-testid', 'accuracy-chart');
  chart.setAttribute('role', 'img');
  chart.setAttribute('aria-label', `Accuracy in the last ${points.length} analysed matches`);
  const step = points.length > 1 ? (CHART_W - 8) / (points.length - 1) : 0;
  const xy = points.map((a, i) => [4 + i * step, CHART_H - 4 - (a / 100) * (CHART_H - 8)]);
  const line = document.createElementNS(SVG, 'polyline');
  line.setAttribute('points', xy.map(([x, y]) => `${x.toFixed(1)},${y.toFixed(1)}`).join(' '));
  chart.append(line);
  for (const [x, y] of xy) {
    const dot = document.createElementNS(SVG, 'circle');
    dot.setAttribute('cx', x.toFixed(1));
    dot.setAttribute('cy', y.toFixed(1));
    dot.setAttribute('r', '3');
    chart.append(dot);
  }
  const last = points[points.length - 1];
  panel.append(chart, el('p', { class: 'small muted', 'data-testid': 'accuracy-last' },
    `Last analysed match: ${last.toFixed(1)} · mean of ${points.length}: ${
      (points.reduce((a, b) => a + b, 0) / points.length).toFixed(1)}`));
  return panel;
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
