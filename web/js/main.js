/**
 * The client shell: routes `/` (lobby) and `/r/{room_id}` (a table), owns the game loop.
 *
 * The loop is javascript-tetris's `frame()`: clamp dt, update (consume queued input, play
 * the frame stream, send throttled aim), draw, requestAnimationFrame. Server messages are
 * reduced into the state as they arrive (state.js); drawing reads the state.
 */

import { api, RoomSocket, memory } from './net.js';
import { initialState, reduce, setConnection, isMyTurn } from './state.js';
import { FramePlayer } from './interpolation.js';
import { placementArea, clampTip, castGuide } from './geometry.js';
import { CELS } from './sprites.js';
import {
  drawBalls, drawGuide, drawCue, drawPlacement, drawPocketCall, drawPowerMeter, drawSinking,
} from './render.js';
import { TableCanvas } from './tablecanvas.js';
import { startReplay } from './replay.js';
import { attachPointer, AimController } from './input.js';
import { TableAudio } from './audio.js';
import {
  $, bindMute, renderRooms, renderHistory, renderHud, renderChat, renderDecision,
} from './ui.js';
import { startLoop } from './loop.js';

const AIM_INTERVAL = 0.1; // seconds between two `aim` messages (the server asks <= 20/s)
const REMOTE_AIM_TTL = 6; // seconds a relayed aim stays drawn without news

const roomMatch = location.pathname.match(/^\/r\/([A-Za-z0-9_-]+)\/?$/);
const matchMatch = location.pathname.match(/^\/m\/([^/]+)\/?$/);
if (roomMatch) startRoom(roomMatch[1]);
else if (matchMatch) startReplay(decodeURIComponent(matchMatch[1]));
else startLobby();

// ---- lobby ---------------------------------------------------------------------------

function startLobby() {
  $('lobby').hidden = false;
  const nameEl = $('name');
  nameEl.value = memory.name();
  nameEl.addEventListener('input', () => memory.setName(nameEl.value.trim()));
  const showError = (msg) => { $('lobby-error').textContent = msg; };
  const needName = () => {
    const name = nameEl.value.trim();
    if (!name) { showError('Enter your name first.'); nameEl.focus(); return null; }
    memory.setName(name);
    return name;
  };
  const joinAndGo = async (roomId, name) => {
    const seat = await api.join(roomId, name);
    memory.setSeat(roomId, { seat: seat.seat, token: seat.token, name: seat.name });
    location.assign(`/r/${roomId}`);
  };
  $('create-room').addEventListener('click', async () => {
    const name = needName();
    if (!name) return;
    const raceTo = Math.min(15, Math.max(1, Number($('race-to').value) || 1));
    try {
      const room = await api.createRoom($('game').value, raceTo);
      await joinAndGo(room.room_id, name);
    } catch (e) { showError(e.message); }
  });
  const refresh = async () => {
    try {
      const { rooms } = await api.listRooms();
      const open = rooms.filter((r) => r.status !== 'finished' || r.spectators > 0);
      renderRooms($('rooms'), open, {
        onJoin: async (id) => {
          const name = needName();
          if (!name) return;
          try { await joinAndGo(id, name); } catch (e) { showError(e.message); refresh(); }
        },
        onWatch: (id) => location.assign(`/r/${id}?watch=1`),
      });
      $('no-rooms').hidden = open.length > 0;
    } catch (e) { showError(`Cannot list tables: ${e.message}`); }
  };
  const refreshHistory = async () => {
    try {
      const { matches } = await api.finishedMatches(10);
      renderHistory($('history'), matches);
      $('no-history').hidden = matches.length > 0;
    } catch (e) { showError(`Cannot list finished matches: ${e.message}`); }
  };
  refresh();
  refreshHistory();
  setInterval(() => { if (!document.hidden) { refresh(); refreshHistory(); } }, 3000);
}

// ---- a table -------------------------------------------------------------------------

function startRoom(roomId) {
  $('room').hidden = false;
  document.title = 'Pool online · table';
  const link = `${location.origin}/r/${roomId}`;
  $('room-link').value = link;
  $('copy-link').addEventListener('click', () => {
    navigator.clipboard?.writeText(link).catch(() => {});
    $('room-link').select();
  });

  let state = initialState({ roomId, name: memory.name() });
  const player = new FramePlayer({ cels: CELS, delay: 0.1 });
  const aim = new AimController();
  const audio = new TableAudio();
  audio.setMuted(memory.muted());
  const inputQueue = [];
  const sounds = []; // {sound, speed, t, shot, at}
  const sinking = []; // balls dropping into a pocket
  let pendingRest = null; // balls at rest waiting for the playback to end
  let pendingCue = null; // where we asked to place the cue ball
  let shotSentAt = -Infinity; // a shot was sent: no more aiming until the server answers
  let lastAimSent = -Infinity;
  let framesSeen = 0;
  let shotsSeen = 0;

  const canvas = $('table');
  const surface = new TableCanvas(canvas, $('table-wrap'));
  let view = null;
  let dpr = 1;
  let sprites = null;

  // -- the socket
  const seatToken = () => memory.seat(roomId)?.token ?? null;
  const socket = new RoomSocket(roomId, seatToken, {
    onMessage: (msg) => receive(msg),
    onStatus: (status, detail) => {
      state = setConnection(state, status);
      if (detail && status === 'closed') state = { ...state, outcome: detail };
    },
  });
  const send = (msg) => socket.send(msg);

  function receive(msg) {
    const now = performance.now() / 1000;
    const prevTable = state.table;
    const res = reduce(state, msg, now);
    state = res.state;
    if (msg.type === 'welcome' && state.me.role === 'spectator' && seatToken()) {
      // The stored token was not accepted as a seat: forget it.
    }
    if (msg.type === 'error' && msg.ref === 'place_cue') pendingCue = null;
    if (msg.type === 'error' && msg.ref === 'shoot') shotSentAt = -Infinity;
    if (msg.type === 'error' && msg.ref === 'aim') state = { ...state, error: null };
    if (state.table && state.table !== prevTable) {
      player.radius = state.table.ball_radius;
    }
    for (const e of res.effects) {
      switch (e.kind) {
        case 'sync': send({ type: 'sync' }); break;
        case 'rest':
          pendingCue = null;
          shotSentAt = -Infinity;
          if (player.done) { player.reset(e.balls); pendingRest = null; } else pendingRest = e.balls;
          break;
        case 'shot':
          shotsSeen += 1;
          shotSentAt = -Infinity;
          pendingRest = null;
          aim.reset();
          player.startShot(e.balls, e.balls ? e.tick / state.tickHz : 0);
          break;
        case 'frame':
          framesSeen += 1;
          player.push({ t: e.t, balls: e.balls, last: e.last, ahead: e.ahead });
          break;
        case 'sound':
          sounds.push({ ...e, at: now });
          break;
        default: break;
      }
    }
  }

  // -- joining a seat or watching
  async function chooseSeat() {
    if (seatToken()) { socket.connect(); return; }
    socket.connect(); // watch while deciding
    const watchOnly = new URLSearchParams(location.search).has('watch');
    let room;
    try { room = await api.getRoom(roomId); } catch (e) {
      state = { ...state, outcome: e.status === 404
        ? 'This table does not exist (or has expired).' : e.message };
      return;
    }
    const free = (room.players ?? []).some((p) => p === null);
    if (!free || watchOnly) return;
    const dialog = $('join-dialog');
    const nameEl = $('join-name');
    nameEl.value = memory.name();
    const names = (room.players ?? []).filter(Boolean);
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
      } catch (e) { $('join-error').textContent = e.message; }
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
    if (confirm('Concede this frame?')) send({ type: 'concede' });
  });
  $('rerack').addEventListener('click', () => send({ type: 'rerack' }));
  $('push-out').addEventListener('click', () => send({ type: 'push_out' }));
  $('chat-form').addEventListener('submit', (ev) => {
    ev.preventDefault();
    const text = $('chat-input').value.trim();
    if (text && send({ type: 'chat', text: text.slice(0, 200) })) $('chat-input').value = '';
  });
  setupSpin();

  function setupSpin() {
    const el = $('spin');
    const dot = el.querySelector('.spin-dot');
    const reach = 0.6; // the widget's edge is this fraction of the radius
    const show = () => {
      dot.style.left = `${50 + (aim.tip[0] / reach) * 50}%`;
      dot.style.top = `${50 - (aim.tip[1] / reach) * 50}%`;
      el.dataset.tip = aim.tip.map((v) => v.toFixed(2)).join(',');
    };
    const set = (ev) => {
      const r = el.getBoundingClientRect();
      const side = ((ev.clientX - r.left) / r.width - 0.5) * 2 * reach;
      const height = -((ev.clientY - r.top) / r.height - 0.5) * 2 * reach;
      aim.tip = clampTip(side, height);
      aim.dirty = true;
      show();
    };
    el.addEventListener('pointerdown', (ev) => { el.setPointerCapture(ev.pointerId); set(ev); });
    el.addEventListener('pointermove', (ev) => { if (ev.buttons) set(ev); });
    el.addEventListener('dblclick', () => { aim.tip = [0, 0]; aim.dirty = true; show(); });
    show();
  }

  // -- the loop
  let balls = new Map();

  function situation() {
    const ballList = [...balls].map(([id, b]) => ({ id, x: b.x, y: b.y }));
    const cueBall = balls.get(0);
    const cue = pendingCue ? [pendingCue.x, pendingCue.y]
      : cueBall ? [cueBall.x, cueBall.y] : null;
    const m = state.match;
    return {
      table: state.table,
      balls: ballList,
      cue,
      myTurn: isMyTurn(state) && state.phase === 'aiming' && !m?.decision
        && performance.now() / 1000 - shotSentAt > 3,
      ballInHand: m?.ball_in_hand ?? null,
      requiresCall: !!m?.requires_call,
    };
  }

  function update(dt, now) {
    // The balls: the stream's playback, or the table at rest.
    const before = balls;
    balls = player.advance(dt);
    if (pendingRest && player.done) { player.reset(pendingRest); pendingRest = null; balls = player.current; }
    if (player.playing && state.table) {
      for (const [id, b] of before) {
        if (!balls.has(id) && !sinking.some((s) => s.id === id)) {
          const pocket = nearestPocket(state.table, b.x, b.y);
          sinking.push({ id, from: [b.x, b.y], to: pocket, cel: b.cel, heading: b.heading ?? 0,
            start: now, duration: 0.18 });
        }
      }
    }
    for (let i = sinking.length - 1; i >= 0; i--) {
      if (now - sinking[i].start > sinking[i].duration) sinking.splice(i, 1);
    }
    // Sounds, in step with the playback.
    for (let i = 0; i < sounds.length; i++) {
      const s = sounds[i];
      const due = !player.playing || s.t <= player.time + 0.01 || now - s.at > 0.6;
      if (due) {
        if (now - s.at < 1.0) audio.play(s.sound, s.speed);
        sounds.splice(i, 1);
        i--;
      }
    }
    // Input.
    const sit = situation();
    while (inputQueue.length) {
      const a = inputQueue.shift();
      if (a.sx !== undefined && view) {
        const [x, y] = view.toTable(a.sx, a.sy);
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

  function draw(now) {
    if (!surface.layout(state.table)) return;
    ({ view, dpr, sprites } = surface);
    const ctx = surface.begin();
    const sit = situation();
    const table = state.table;
    const area = sit.myTurn ? placementArea(table, sit.ballInHand) : null;
    if (area) drawPlacement(ctx, view, area, aim.mode === 'placing' ? { ...aim.placing, r: table.ball_radius } : null);
    let shown = balls;
    const placing = aim.mode === 'placing' && aim.placing ? aim.placing : pendingCue;
    if (placing) {
      shown = new Map(balls);
      shown.set(0, { ...(balls.get(0) ?? { cel: 0, heading: 0 }), x: placing.x, y: placing.y });
    }
    if (sprites) {
      drawBalls(ctx, view, sprites, shown, 1 / dpr);
      for (const s of sinking) drawSinking(ctx, view, sprites, s, now, 1 / dpr);
    }
    const cue = placing ? [placing.x, placing.y] : sit.cue;
    if (state.phase === 'aiming' && cue && aim.mode !== 'placing') {
      if (sit.myTurn) {
        drawGuide(ctx, view, table, cue, aim.guide(table, sit.balls, cue));
        drawCue(ctx, view, table, cue, aim.angle, aim.power);
        if (aim.mode === 'pulling') drawPowerMeter(ctx, view, cue, aim.power);
      } else if (state.aim && state.aim.seat !== state.me.seat
                 && now - state.aim.at < REMOTE_AIM_TTL) {
        drawGuide(ctx, view, table, cue, castGuide(table, sit.balls, cue, state.aim.angle));
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
    renderDecision(state, (option) => send({ type: 'decide', option }));
  });

  // Read-only hook for automated tests and debugging.
  window.__pool = {
    get state() { return state; },
    get balls() { return [...balls].map(([id, b]) => ({ id, x: b.x, y: b.y, cel: b.cel })); },
    get framesSeen() { return framesSeen; },
    get shotsSeen() { return shotsSeen; },
    get playing() { return player.playing && !player.done; },
    get ready() { return !!(view && sprites); },
    /** Table metres -> CSS pixels relative to the canvas's top-left corner. */
    toScreen(x, y) { return view ? view.toScreen(x, y) : null; },
    get aim() { return { angle: aim.angle, power: aim.power, mode: aim.mode, tip: aim.tip }; },
  };
}

function nearestPocket(table, x, y) {
  let best = table.pockets[0].center;
  let bestD = Infinity;
  for (const p of table.pockets) {
    const d = Math.hypot(p.center[0] - x, p.center[1] - y);
    if (d < bestD) { bestD = d; best = p.center; }
  }
  return best;
}
