/**
 * A live table (`/r/{room_id}`): the room is looked up first; a link to a table that does
 * not exist gets a page that says so, and no socket is opened for it. Otherwise the table
 * (table/live.js: the socket, the aim, the shared table view) is built, its controls and
 * the seat dialog bound, and the display loop runs its `update` then `draw` each frame.
 */

import { api } from '../net.js';
import { $ } from '../ui.js';
import { startLoop } from '../loop.js';
import { LiveTable } from './table/live.js';
import { bindControls, bindRoomLink } from './table/controls.js';
import { chooseSeat } from './table/seat.js';

/** @param {string} roomId */
export function startTable(roomId) {
  document.title = 'Pool online · table';
  api.getRoom(roomId).then((room) => openTable(roomId, room), (e) => {
    const err = /** @type {import('../net.js').ApiError} */ (e);
    if (err.status === 404 || err.status === 422) showMissing();
    else openTable(roomId, null); // the server is unreachable now: the socket retries
  });
}

/** The page for a link to a table that does not exist (or expired): no socket, no retries. */
function showMissing() {
  document.title = 'Pool online · no such table';
  $('missing').hidden = false;
  /** @type {any} */ (window).__pool = { missing: true, ready: false };
}

/**
 * @param {string} roomId
 * @param {any} room `GET /api/rooms/{room_id}` (null when it could not be read)
 */
function openTable(roomId, room) {
  $('room').hidden = false;
  bindRoomLink(`${location.origin}/r/${roomId}`);
  const live = new LiveTable(roomId);
  chooseSeat(roomId, room, live.socket);
  bindControls(live);
  startLoop((dt, now) => {
    live.update(dt, now);
    live.draw(now);
  });
  /** @type {any} */ (window).__pool = testHook(live);
}

/**
 * Read-only hook for automated tests and debugging.
 * @param {LiveTable} live
 */
function testHook(live) {
  const { playback, aim } = live;
  return {
    get state() { return live.state; },
    get balls() { return live.view.ballList(); },
    get framesSeen() { return playback.framesSeen; },
    get shotsSeen() { return live.shotsSeen; },
    get playing() { return playback.busy; },
    get shotTime() { return playback.time; },
    get ready() { return live.view.ready; },
    /**
     * Table metres -> CSS pixels relative to the canvas's top-left corner.
     * @param {number} x
     * @param {number} y
     */
    toScreen(x, y) { return live.view.surface.view?.toScreen(x, y) ?? null; },
    get aim() {
      return { angle: aim.angle, power: aim.power, mode: aim.mode, tip: aim.tip,
        elevation: aim.elevation };
    },
    get objectGuide() { return live.objectGuide; },
    get ticks() { return live.ticks; },
    get remoteCue() { return live.remoteCue; },
    get pendingCue() { return live.pendingCue; },
  };
}
