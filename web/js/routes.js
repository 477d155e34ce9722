/**
 * Which screen a page address shows: `/` the lobby, `/r/{room_id}` a table (playing or
 * watching), `/m/{match_id}` a finished match replayed, `/profile` your profile,
 * `/p/{player_id}` anyone's, `/leaderboard` the ranking, `/login` signing in to an account.
 * Anything else falls back to the lobby. Pure, so the routing is tested without a browser.
 */

/**
 * @typedef {{screen: 'lobby'}
 *   | {screen: 'table', roomId: string}
 *   | {screen: 'replay', matchId: string}
 *   | {screen: 'profile', playerId: string | null}
 *   | {screen: 'leaderboard'}
 *   | {screen: 'login'}} Route
 */

/**
 * @param {string} pathname `location.pathname`
 * @returns {Route}
 */
export function routeOf(pathname) {
  if (/^\/profile\/?$/.test(pathname)) return { screen: 'profile', playerId: null };
  const player = pathname.match(/^\/p\/([A-Za-z0-9_-]+)\/?$/);
  if (player) return { screen: 'profile', playerId: player[1] };
  if (/^\/leaderboard\/?$/.test(pathname)) return { screen: 'leaderboard' };
  if (/^\/login\/?$/.test(pathname)) return { screen: 'login' };
  const room = pathname.match(/^\/r\/([A-Za-z0-9_-]+)\/?$/);
  if (room) return { screen: 'table', roomId: room[1] };
  const match = pathname.match(/^\/m\/([^/]+)\/?$/);
  if (match) {
    let matchId = match[1];
    // A malformed escape is not a match id either; the replay says there is no such match.
    try { matchId = decodeURIComponent(matchId); } catch { /* keep it as it came */ }
    return { screen: 'replay', matchId };
  }
  return { screen: 'lobby' };
}
