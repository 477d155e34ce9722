/**
 * The client's entry point: picks the screen for the page's address and starts its
 * controller. Each screen owns its DOM section, its state and its loop:
 *
 *  - `/`             screens/lobby.js   open tables, finished matches, creating a table
 *  - `/r/{room_id}`  screens/table.js   a live table (play or watch)
 *  - `/m/{match_id}` screens/replay.js  a finished match, shot by shot
 *  - `/profile`, `/p/{player_id}` screens/profile.js  a player's name, ratings, matches
 *  - `/leaderboard`  screens/leaderboard.js  the ranking per game
 *  - `/login`        screens/login.js   signing in with a passkey or a password
 */

import { routeOf } from './routes.js';
import { shownTrack } from './playback.js';
import { startLobby } from './screens/lobby.js';
import { startTable } from './screens/table.js';
import { startReplay } from './screens/replay.js';
import { startProfile } from './screens/profile.js';
import { startLeaderboard } from './screens/leaderboard.js';
import { startLogin } from './screens/login.js';

const route = routeOf(location.pathname);
if (route.screen === 'table') startTable(route.roomId);
else if (route.screen === 'replay') startReplay(route.matchId);
else if (route.screen === 'profile') startProfile(route.playerId);
else if (route.screen === 'leaderboard') startLeaderboard();
else if (route.screen === 'login') startLogin();
else startLobby();

// A contract for outside tests: what the renderer would draw t seconds after the strike of
// the shot being shown (or the last one shown, until the next starts): [{id, x, y, cel}] in
// table metres, the balls on the table at t.
/** @type {any} */ (window).pool = Object.freeze({
  /** @param {number} t */
  track: (t) => shownTrack(t),
});
