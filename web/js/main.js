/**
 * The client's entry point: picks the screen for the page's address and starts its
 * controller. Each screen owns its DOM section, its state and its loop:
 *
 *  - `/`             screens/lobby.js   open tables, finished matches, creating a table
 *  - `/r/{room_id}`  screens/table.js   a live table (play or watch)
 *  - `/m/{match_id}` screens/replay.js  a finished match, shot by shot
 */

import { routeOf } from './routes.js';
import { startLobby } from './screens/lobby.js';
import { startTable } from './screens/table.js';
import { startReplay } from './screens/replay.js';

const route = routeOf(location.pathname);
if (route.screen === 'table') startTable(route.roomId);
else if (route.screen === 'replay') startReplay(route.matchId);
else startLobby();
