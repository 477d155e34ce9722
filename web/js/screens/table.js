/**
 * A live table (`/r/{room_id}`): the room's WebSocket, the seat dialog, the input, and the
 * display loop (javascript-tetris's `frame()`: update — consume queued input, play the shot
 * stream, send throttled aim — then draw). Server messages are reduced into the state as
 * they arrive (state.js); the shot's frames, sounds and pocketed balls go to the shared
 * playback (playback.js); drawing reads both.
 */

import { api, RoomSocket, memory } from '../net.js';
import { initialState, reduce, setConnection, isMyTurn } from '../state.js';
import { ShotPlayback } from '../playback.js';
import { placementArea, clampTip, castGuide, squirt } from '../geometry.js';
import { CELS } from '../sprites.js';
import {
  drawBalls, drawGuide, drawCue, drawPlacement, drawPocketCall, drawPowerMeter, drawSinking,
} from '../render.js';
import { TableCanvas } from '../tablecanvas.js';
import { attachPointer, AimController } from '../input.js';
import { TableAudio } from '../audio.js';
import {
  $, $input, applyInputLimits, bindMute, renderHud, renderChat, renderDecision,
} from '../ui.js';
import { startLoop } from '../loop.js';

const AIM_INTERVAL = 0.1; // seconds between two `aim` messages (the server asks <= 20/s)
const REMOTE_AIM_TTL = 6; // seconds a relayed aim stays drawn without news
const SHOT_ANSWER_WAIT = 3; // seconds without aiming after a shot is sent, awaiting the server
const SPIN_REACH = 1.2; // the spin widget's edge, as a multiple of the largest legal tip

/** @param {string} roomId */
export function startTable(roomId) {
  $('room').hidden = false;
  document.title = 'Pool online · table';
  const link = `${location.origin}/r/${roomId}`;
  $input('room-link').value = link;
  $('copy-link').addEventListener('click', () => {
    navigator.clipboard?.writeText(link).catch(() => {});
    $input('room-link').select();
  });

  let state = initialState({ roomId, name: memory.name() });
  /** The game (frame) of the match now: what a concession or a decision is meant for. */
  const currentGame = () => (state.match?.games_played ?? 0) + 1;
  const audio = new TableAudio();
  audio.setMuted(memory.muted());
  const playback = new ShotPlayback({ cels: CELS, delay: 0.1,
    onSound: (sound, speed) => audio.play(sound, speed) });
  const aim = new AimController();
  /** @type {import('../input.js').PointerAction[]} */
  const inputQueue = [];
  /** @type {{x: number, y: number} | null} where we asked to place the cue ball */
  let pendingCue = null;
  let shotSentAt = -Infinity; // a shot was sent: no more aiming until the server answers
  let lastAimSent = -Infinity;
  let shotsSeen = 0;
  let limits = state.limits;
  applyInputLimits(limits);

  const canvas = /** @type {HTMLCanvasElement} */ ($('table'));
  const surface = new TableCanvas(canvas, $('table-wrap'));

  // -- the socket
  const seatToken = () => memory.seat(roomId)?.token ?? null;
  const socket = new RoomSocket(roomId, seatToken, {
    onMessage: (msg) => receive(msg),
    onStatus: (status, detail) => {
      state = setConnection(state, status);
      if (detail && status === 'closed') state = { ...state, outcome: detail };
    },
  });
  /** @param {Record<string, any>} msg */
  const send = (msg) => socket.send(msg);

  /** @param {Record<string, any>} msg */
  function receive(msg) {
    const now = performance.now() / 1000;
    const res = reduce(state, msg, now);
    state = res.state;
    if (msg.type === 'error' && msg.ref === 'place_cue') pendingCue = null;
    if (msg.type === 'error' && msg.ref === 'shoot') shotSentAt = -Infinity;
    if (msg.type === 'error' && msg.ref === 'aim') state = { ...state, error: null };
    playback.setTable(state.table);
    if (state.limits !== limits) {
      limits = state.limits;
      applyInputLimits(limits);
      aim.tip = clampTip(aim.tip[0], aim.tip[1], limits.max_tip);
      showSpin();
    }
    for (const e of res.effects) {
      switch (e.kind) {
        case 'sync': send({ type: 'sync' }); break;
        case 'rest':
          pendingCue = null;
          shotSentAt = -Infinity;
          break;
        case 'shot':
          shotsSeen += 1;
          shotSentAt = -Infinity;
          aim.reset();
          break;
        default: break;
      }
      playback.apply(e, now);
    }
  }

  // -- joining a seat or watching
  async function chooseSeat() {
    if (seatToken()) { socket.connect(); return; }
    socket.connect(); // watch while deciding
    const watchOnly = new URLSearchParams(location.search).has('watch');
    let room;
    try { room = await api.getRoom(roomId); } catch (e) {
      const err = /** @type {import('../net.js').ApiError} */ (e);
      state = { ...state, outcome: err.status === 404
        ? 'This table does not exist (or has expired).' : err.message };
      return;
    }
    /** @type {(string | null)[]} */
    const players = room.players ?? [];
    const free = players.some((p) => p === null);
    if (!free || watchOnly) return;
    const dialog = $('join-dialog');
    const nameEl = $input('join-name');
    nameEl.value = memory.name();
    const names = players.filter(Boolean);
    $('join-info').textContent = names.length
      ? `${names.join(' and ')} ${names.length > 1 ? 'are' : 'is'} waiting for an opponent.`
      : 'This table has a free seat.';
    dialog.hidden = false;
    $('watch-only').onclick = () => { dialog.hidden = true; };
    $('join-seat').onclick = async () => {
      const name = nameEl.value.trim();
      if (!name) { $('join-error').textContent = 'Enter your name first.'; return; }
      memory.setName(name);
      try {
        const seat = await api.join(roomId, name);
        memory.setSeat(roomId, { seat: seat.seat, token: seat.token, name: seat.name });
        dialog.hidden = true;
        socket.reconnect();
      } catch (e) { $('join-error').textContent = e instanceof Error ? e.message : String(e); }
    };
  }
  chooseSeat();

  // -- input
  attachPointer(canvas, inputQueue);
  const unlockAudio = () => audio.unlock();
  window.addEventListener('pointerdown', unlockAudio);
  window.addEventListener('keydown', (ev) => {
    unlockAudio();
    if (ev.key === 'Escape') inputQueue.push({ type: 'cancel' });
  });
  bindMute($('mute'), audio, (muted) => memory.setMuted(muted));
  $('rematch').addEventListener('click', () => send({ type: 'rematch' }));
  $('concede').addEventListener('click', () => {
    // Naming the game makes a concession sent just as the frame ended harmless.
    if (confirm('Concede this frame?')) send({ type: 'concede', game: currentGame() });
  });
  $('rerack').addEventListener('click', () => send({ type: 'rerack' }));
  $('push-out').addEventListener('click', () => send({ type: 'push_out' }));
  $('chat-form').addEventListener('submit', (ev) => {
    ev.preventDefault();
    const input = $input('chat-input');
    const text = input.value.trim();
    if (text && send({ type: 'chat', text: text.slice(0, limits.max_chat) })) input.value = '';
  });

  // -- the spin widget: where the cue tip strikes, within the server's `max_tip`
  const spinEl = $('spin');
  const spinDot = /** @type {HTMLElement} */ (spinEl.querySelector('.spin-dot'));
  const spinReach = () => limits.max_tip * SPIN_REACH;
  function showSpin() {
    spinDot.style.left = `${50 + (aim.tip[0] / spinReach()) * 50}%`;
    spinDot.style.top = `${50 - (aim.tip[1] / spinReach()) * 50}%`;
    spinEl.dataset.tip = aim.tip.map((v) => v.toFixed(2)).join(',');
  }
  /** @param {PointerEvent} ev */
  const setSpin = (ev) => {
    const r = spinEl.getBoundingClientRect();
    const side = ((ev.clientX - r.left) / r.width - 0.5) * 2 * spinReach();
    const height = -((ev.clientY - r.top) / r.height - 0.5) * 2 * spinReach();
    aim.tip = clampTip(side, height, limits.max_tip);
    aim.dirty = true;
    showSpin();
  };
  spinEl.addEventListener('pointerdown', (ev) => {
    spinEl.setPointerCapture(ev.pointerId);
    setSpin(ev);
  });
  spinEl.addEventListener('pointermove', (ev) => { if (ev.buttons) setSpin(ev); });
  spinEl.addEventListener('dblclick', () => { aim.tip = [0, 0]; aim.dirty = true; showSpin(); });
  showSpin();

  // -- the loop
  /** @returns {import('../input.js').Situation} */
  function situation() {
    const ballList = [...playback.balls].map(([id, b]) => ({ id, x: b.x, y: b.y }));
    const cueBall = playback.balls.get(0);
    /** @type {[number, number] | null} */
    const cue = pendingCue ? [pendingCue.x, pendingCue.y]
      : cueBall ? [cueBall.x, cueBall.y] : null;
    const m = state.match;
    return {
      table: state.table,
      balls: ballList,
      cue,
      myTurn: isMyTurn(state) && state.phase === 'aiming' && !m?.decision
        && performance.now() / 1000 - shotSentAt > SHOT_ANSWER_WAIT,
      ballInHand: m?.ball_in_hand ?? null,
      requiresCall: !!m?.requires_call,
      limits,
    };
  }

  /**
   * @param {number} dt
   * @param {number} now
   */
  function update(dt, now) {
    playback.update(dt, now);
    const sit = situation();
    while (inputQueue.length) {
      const a = /** @type {import('../input.js').PointerAction} */ (inputQueue.shift());
      if (a.sx !== undefined && a.sy !== undefined && surface.view) {
        const [x, y] = surface.view.toTable(a.sx, a.sy);
        a.x = x; a.y = y;
      }
      for (const msg of aim.handle(a, sit)) {
        if (msg.type === 'place_cue') pendingCue = { x: msg.x, y: msg.y };
        if (msg.type === 'shoot') { shotSentAt = now; aim.dirty = false; }
        send(msg);
      }
    }
    if (!sit.myTurn && aim.mode !== 'idle') aim.reset();
    if (sit.myTurn && aim.dirty && now - lastAimSent >= AIM_INTERVAL) {
      aim.dirty = false;
      lastAimSent = now;
      send({ type: 'aim', angle: Math.round(aim.angle * 1e4) / 1e4,
        power: Math.round(aim.power * 1000) / 1000, tip: aim.tip });
    }
  }

  /** @param {number} now */
  function draw(now) {
    if (!surface.layout(state.table)) return;
    const { view, dpr, sprites } = surface;
    const ctx = surface.begin();
    const sit = situation();
    const table = state.table;
    const area = sit.myTurn ? placementArea(table, sit.ballInHand) : null;
    if (area) {
      drawPlacement(ctx, view, area,
        aim.mode === 'placing' && aim.placing ? { ...aim.placing, r: table.ball_radius } : null);
    }
    let shown = playback.balls;
    const placing = aim.mode === 'placing' && aim.placing ? aim.placing : pendingCue;
    if (placing) {
      shown = new Map(shown);
      const cueBall = shown.get(0) ?? { cel: 0, heading: 0, speed: 0 };
      shown.set(0, { ...cueBall, x: placing.x, y: placing.y });
    }
    if (sprites) {
      drawBalls(ctx, view, sprites, shown, 1 / dpr);
      for (const s of playback.sinking.list) drawSinking(ctx, view, sprites, s, now, 1 / dpr);
    }
    /** @type {[number, number] | null} */
    const cue = placing ? [placing.x, placing.y] : sit.cue;
    if (state.phase === 'aiming' && cue && aim.mode !== 'placing') {
      if (sit.myTurn) {
        drawGuide(ctx, view, table, cue, aim.guide(table, sit.balls, cue, limits.cue_mass_ratio));
        drawCue(ctx, view, table, cue, aim.angle, aim.power);
        if (aim.mode === 'pulling') drawPowerMeter(ctx, view, cue, aim.power);
      } else if (state.aim && state.aim.seat !== state.me.seat
                 && now - state.aim.at < REMOTE_AIM_TTL) {
        const path = state.aim.angle + squirt(state.aim.tip[0] ?? 0, limits.cue_mass_ratio);
        drawGuide(ctx, view, table, cue, castGuide(table, sit.balls, cue, path));
        drawCue(ctx, view, table, cue, state.aim.angle, state.aim.power, 0.85);
        if (state.aim.power > 0) drawPowerMeter(ctx, view, cue, state.aim.power);
      }
    }
    if (sit.myTurn && sit.requiresCall) {
      drawPocketCall(ctx, view, table, state.match?.called_pocket ?? -1, aim.hoverPocket,
        0.5 + 0.5 * Math.sin(now * 4));
    } else if (state.match?.called_pocket != null && state.phase !== 'waiting') {
      drawPocketCall(ctx, view, table, state.match.called_pocket, -1, 0);
    }
  }

  startLoop((dt, now) => {
    update(dt, now);
    draw(now);
    renderHud(state, now);
    renderChat(state);
    renderDecision(state, (option) => send({ type: 'decide', option, game: currentGame() }));
  });

  // Read-only hook for automated tests and debugging.
  /** @type {any} */ (window).__pool = {
    get state() { return state; },
    get balls() {
      return [...playback.balls].map(([id, b]) => ({ id, x: b.x, y: b.y, cel: b.cel }));
    },
    get framesSeen() { return playback.framesSeen; },
    get shotsSeen() { return shotsSeen; },
    get playing() { return playback.busy; },
    get ready() { return !!(surface.view && surface.sprites); },
    /**
     * Table metres -> CSS pixels relative to the canvas's top-left corner.
     * @param {number} x
     * @param {number} y
     */
    toScreen(x, y) { return surface.view ? surface.view.toScreen(x, y) : null; },
    get aim() { return { angle: aim.angle, power: aim.power, mode: aim.mode, tip: aim.tip }; },
  };
}
