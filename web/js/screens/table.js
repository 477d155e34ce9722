/**
 * A live table (`/r/{room_id}`): the room's WebSocket, the seat dialog, the input, and the
 * display loop (javascript-tetris's `frame()`: update — consume queued input, play the shot
 * stream, send throttled aim — then draw). Server messages are reduced into the state as
 * they arrive (state.js); the shot's frames, sounds and pocketed balls go to the shared
 * playback (playback.js); drawing reads both.
 *
 * The room is looked up first: a link to a table that does not exist gets a page that says
 * so, and no socket is opened for it.
 */

import { api, RoomSocket, memory } from '../net.js';
import {
  initialState, reduce, setConnection, isMyTurn, clockRemaining, playerName,
} from '../state.js';
import { ShotPlayback } from '../playback.js';
import { players as playerApi } from '../players.js';
import {
  placementArea, clampTip, castGuide, squirt, objectPath,
} from '../geometry.js';
import { CELS } from '../sprites.js';
import {
  drawBalls, drawGuide, drawCue, drawPlacement, drawPocketCall, drawPowerMeter, drawSinking,
  drawClockRing,
} from '../render.js';
import { TableCanvas } from '../tablecanvas.js';
import { attachPointer, AimController } from '../input.js';
import { TableAudio } from '../audio.js';
import {
  $, $input, applyInputLimits, bindMute, renderHud, renderChat, renderDecision, renderAway,
  setText, URGENT_AT,
} from '../ui.js';
import { Coach } from '../coach.js';
import { ShotHint } from '../hint.js';
import { icon } from '../icons.js';
import { startLoop } from '../loop.js';

const AIM_INTERVAL = 0.1; // seconds between two `aim` messages (the server asks <= 20/s)
const REMOTE_AIM_TTL = 6; // seconds a relayed aim stays drawn without news
const REMOTE_CUE_TTL = 3; // seconds a relayed cue-ball drag stays drawn without news
const SHOT_ANSWER_WAIT = 3; // seconds without aiming after a shot is sent, awaiting the server
const SPIN_REACH = 1.2; // the spin widget's edge, as a multiple of the largest legal tip
const FEEDBACK_FOR = 2.5; // seconds a "shot cancelled" / "drop refused" note stays up
const FRAME_BANNER_FOR = 3.5; // seconds the frame-won banner stays up
const FINE_STEP = 0.002; // radians per fine-aim step (x10 with Shift)
const TOUCH_LIFT = 44; // CSS px the dragged cue ball is drawn above a finger
/** @type {Record<string, string>} */
const GAME_NAMES = { eight_ball: '8-ball', nine_ball: '9-ball', practice: 'Practice' };

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
  const link = `${location.origin}/r/${roomId}`;
  $input('room-link').value = link;
  const copyButton = $('copy-link');
  copyButton.addEventListener('click', async () => {
    $input('room-link').select();
    let copied = false;
    try { await navigator.clipboard.writeText(link); copied = true; } catch { /* below */ }
    if (!copied) {
      try { copied = document.execCommand('copy'); } catch { copied = false; }
    }
    copyButton.replaceChildren(...(copied ? [icon('check', 16), ' Copied'] : ['Select + copy']));
    copyButton.dataset.copied = String(copied);
    setTimeout(() => { copyButton.textContent = 'Copy'; delete copyButton.dataset.copied; }, 2000);
  });

  let state = initialState({ roomId, name: memory.name() });
  /** The game (frame) of the match now: what a concession or a decision is meant for. */
  const currentGame = () => (state.match?.games_played ?? 0) + 1;
  const audio = new TableAudio();
  audio.setMuted(memory.muted());
  const playback = new ShotPlayback({ cels: CELS, delay: 0.1,
    onSound: (sound, speed) => audio.play(sound, speed) });
  const aim = new AimController();
  const coach = new Coach($('coach'), $('coach-ok'));
  const hint = new ShotHint(/** @type {HTMLButtonElement} */ ($('hint')), $('hint-text'),
    roomId, () => seatToken());
  /** @type {import('../input.js').PointerAction[]} */
  const inputQueue = [];
  /** @type {{x: number, y: number} | null} where we asked to place the cue ball */
  let pendingCue = null;
  let shotSentAt = -Infinity; // a shot was sent: no more aiming until the server answers
  let lastAimSent = -Infinity;
  let lastCueSent = '';
  let shotsSeen = 0;
  let graceAt = 0; // local time the grace list came
  /** @type {{x: number, y: number, seat: number, at: number} | null} another's cue-ball drag */
  let remoteCue = null;
  let feedbackSeq = 0;
  /** @type {{text: string, kind: string, until: number}} */
  let feedback = { text: '', kind: '', until: 0 };
  /** @type {{text: string, until: number}} */
  let frameBanner = { text: '', until: 0 };
  let lastTick = -1;
  let ticks = 0;
  const keepSpinEl = $input('keep-spin');
  keepSpinEl.checked = localStorage.getItem('pool.keepSpin') === '1';
  keepSpinEl.addEventListener('change', () => {
    localStorage.setItem('pool.keepSpin', keepSpinEl.checked ? '1' : '0');
  });
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
    const before = state;
    const res = reduce(state, msg, now);
    state = res.state;
    if (msg.type === 'error' && msg.ref === 'place_cue') pendingCue = null;
    if (msg.type === 'error' && msg.ref === 'shoot') shotSentAt = -Infinity;
    if (msg.type === 'error' && msg.ref === 'aim') state = { ...state, error: null };
    if (msg.type === 'state' || msg.type === 'presence') graceAt = now;
    if (msg.type === 'state' && Array.isArray(msg.chat)) {
      // The room's last lines (sent on connecting): a reload keeps the conversation.
      state = { ...state, chat: msg.chat.map((/** @type {any} */ c) =>
        ({ seat: c.seat, name: c.name, text: c.text })) };
    }
    if (msg.type === 'aim') {
      remoteCue = Array.isArray(msg.cue)
        ? { x: msg.cue[0], y: msg.cue[1], seat: msg.seat, at: now } : null;
    }
    if (msg.type === 'state') {
      if (state.phase !== 'aiming') remoteCue = null;
      if (before.phase === 'over' && state.phase === 'aiming') {
        // A rematch began: last match's words are history.
        state = { ...state, outcome: '' };
        frameBanner = { text: '', until: 0 };
      }
    }
    playback.setTable(state.table);
    if (state.limits !== limits) {
      limits = state.limits;
      applyInputLimits(limits);
      aim.tip = clampTip(aim.tip[0], aim.tip[1], limits.max_tip);
    }
    for (const e of res.effects) {
      switch (e.kind) {
        case 'sync': send({ type: 'sync' }); break;
        case 'rest':
          pendingCue = null;
          shotSentAt = -Infinity;
          break;
        case 'motion': // a shot starts (or, joining, goes on) on this page
          shotsSeen += 1;
          hint.clear();
          shotSentAt = -Infinity;
          aim.reset();
          remoteCue = null;
          // The last shot's words go stale as the next one is played.
          state = { ...state, outcome: '' };
          if (!keepSpinEl.checked) aim.tip = [0, 0];
          break;
        case 'result': {
          const o = e.result?.outcome;
          if (o?.frame_over && o.winner != null && !e.result.match_over) {
            const score = Array.isArray(e.result.score) ? ` · ${e.result.score.join(' – ')}` : '';
            frameBanner = { text: `${playerName(state, o.winner) ?? 'A player'} wins the frame`
              + score, until: now + FRAME_BANNER_FOR };
          }
          break;
        }
        default: break;
      }
      playback.apply(e, now);
    }
  }

  // -- joining a seat or watching
  function chooseSeat() {
    socket.connect(); // watch while deciding
    if (seatToken() || !room) return;
    const watchOnly = new URLSearchParams(location.search).has('watch');
    /** @type {(string | null)[]} */
    const players = room.players ?? [];
    const free = players.some((p) => p === null);
    if (!free || watchOnly) return;
    const dialog = $('join-dialog');
    const nameEl = $input('join-name');
    nameEl.value = memory.name();
    const names = players.filter(Boolean);
    const game = GAME_NAMES[room.game] ?? room.game;
    const what = room.game === 'practice' ? 'A practice table.'
      : `${game} · race to ${room.race_to}`
        + (room.shot_clock > 0 ? ` · ${Math.round(room.shot_clock)} s shot clock.` : '.');
    $('join-info').textContent = `${what} ${names.length
      ? `${names.join(' and ')} ${names.length > 1 ? 'are' : 'is'} waiting for an opponent.`
      : 'This table has a free seat.'}${room.ranked
      ? ' This table is ranked: your rating will change.' : ''}`;
    // Joining a ranked table is the player's agreement to be rated.
    $('join-seat').textContent = room.ranked ? 'Join the ranked game' : 'Join the game';
    dialog.hidden = false;
    $('watch-only').onclick = () => { dialog.hidden = true; };
    $('join-seat').onclick = async () => {
      const name = nameEl.value.trim();
      if (!name) { $('join-error').textContent = 'Enter your name first.'; return; }
      memory.setName(name);
      try {
        // A ranked seat needs a profile: made here when the link is the first visit.
        if (room?.ranked) await playerApi.me();
        const seat = await api.join(roomId, name, Boolean(room?.ranked));
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
  /** @param {number} delta */
  const nudge = (delta) => { if (situation().myTurn && aim.mode !== 'placing') aim.nudge(delta); };
  window.addEventListener('keydown', (ev) => {
    unlockAudio();
    if (ev.key === 'Escape') inputQueue.push({ type: 'cancel' });
    const typing = ev.target instanceof HTMLInputElement || ev.target instanceof HTMLSelectElement;
    if (typing) return;
    const step = FINE_STEP * (ev.shiftKey ? 10 : 1);
    if (ev.key === 'ArrowLeft' || ev.key === 'ArrowDown') { nudge(step); ev.preventDefault(); }
    if (ev.key === 'ArrowRight' || ev.key === 'ArrowUp') { nudge(-step); ev.preventDefault(); }
  });
  canvas.addEventListener('wheel', (ev) => {
    if (!situation().myTurn) return;
    ev.preventDefault();
    nudge((ev.deltaY > 0 ? -1 : 1) * FINE_STEP * (ev.shiftKey ? 10 : 1));
  }, { passive: false });
  for (const [id, sign] of /** @type {[string, number][]} */ ([['aim-left', 1], ['aim-right', -1]])) {
    const button = $(id);
    /** @type {ReturnType<typeof setInterval> | undefined} */
    let repeat;
    const stop = () => { clearInterval(repeat); repeat = undefined; };
    button.addEventListener('pointerdown', (ev) => {
      ev.preventDefault();
      nudge(sign * FINE_STEP);
      stop();
      let n = 0;
      repeat = setInterval(() => { n += 1; if (n > 4) nudge(sign * FINE_STEP * (n > 20 ? 4 : 1)); },
        60);
    });
    for (const end of ['pointerup', 'pointerleave', 'pointercancel']) {
      button.addEventListener(end, stop);
    }
    button.addEventListener('keydown', (ev) => {
      if (ev.key === 'Enter' || ev.key === ' ') { ev.preventDefault(); nudge(sign * FINE_STEP); }
    });
  }
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

  // -- the spin widget: where the cue tip strikes, within the server's `max_tip`; while
  // another player is at the table it shows their spin (from the relayed `aim`).
  const spinEl = $('spin');
  const spinDot = /** @type {HTMLElement} */ (spinEl.querySelector('.spin-dot'));
  const spinReach = () => limits.max_tip * SPIN_REACH;
  /** @param {number[]} tip */
  function showSpin(tip) {
    const key = tip.map((v) => v.toFixed(2)).join(',');
    if (spinEl.dataset.tip === key) return;
    spinDot.style.left = `${50 + (tip[0] / spinReach()) * 50}%`;
    spinDot.style.top = `${50 - (tip[1] / spinReach()) * 50}%`;
    spinEl.dataset.tip = key;
  }
  /** @param {PointerEvent} ev */
  const setSpin = (ev) => {
    const r = spinEl.getBoundingClientRect();
    const side = ((ev.clientX - r.left) / r.width - 0.5) * 2 * spinReach();
    const height = -((ev.clientY - r.top) / r.height - 0.5) * 2 * spinReach();
    aim.tip = clampTip(side, height, limits.max_tip);
    aim.dirty = true;
  };
  spinEl.addEventListener('pointerdown', (ev) => {
    spinEl.setPointerCapture(ev.pointerId);
    setSpin(ev);
  });
  spinEl.addEventListener('pointermove', (ev) => { if (ev.buttons) setSpin(ev); });
  spinEl.addEventListener('dblclick', () => { aim.tip = [0, 0]; aim.dirty = true; });

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
   * The spin shown: the shooter's own, or the relayed spin of the player at the table.
   * @param {number} now
   * @returns {number[]}
   */
  function shownTip(now) {
    if (situation().myTurn || !state.aim || state.aim.seat === state.me.seat
        || now - state.aim.at > REMOTE_AIM_TTL || state.phase !== 'aiming') return aim.tip;
    return state.aim.tip;
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
        // A cue ball dragged by a finger is held above it, where the player can see it.
        const lift = a.pointerType === 'touch' && aim.mode === 'placing' && a.type !== 'down'
          ? TOUCH_LIFT : 0;
        const [x, y] = surface.view.toTable(a.sx, a.sy - lift);
        a.x = x; a.y = y;
      }
      for (const msg of aim.handle(a, sit)) {
        if (msg.type === 'place_cue') pendingCue = { x: msg.x, y: msg.y };
        if (msg.type === 'shoot') { shotSentAt = now; aim.dirty = false; coach.done(); }
        send(msg);
      }
    }
    if (aim.feedback.seq !== feedbackSeq) {
      feedbackSeq = aim.feedback.seq;
      feedback = { text: aim.feedback.text, kind: aim.feedback.kind, until: now + FEEDBACK_FOR };
    }
    if (!sit.myTurn && aim.mode !== 'idle') aim.reset();
    const dragged = aim.mode === 'placing' && aim.placing
      ? `${aim.placing.x.toFixed(3)},${aim.placing.y.toFixed(3)}` : '';
    if (sit.myTurn && dragged !== lastCueSent) { aim.dirty = true; }
    if (sit.myTurn && aim.dirty && now - lastAimSent >= AIM_INTERVAL) {
      aim.dirty = false;
      lastAimSent = now;
      lastCueSent = dragged;
      /** @type {Record<string, any>} */
      const msg = { type: 'aim', angle: Math.round(aim.angle * 1e4) / 1e4,
        power: Math.round(aim.power * 1000) / 1000, tip: aim.tip };
      if (aim.mode === 'placing' && aim.placing) {
        msg.cue = [Math.round(aim.placing.x * 1e4) / 1e4, Math.round(aim.placing.y * 1e4) / 1e4];
      }
      send(msg);
    }
    // The shot clock's last seconds tick for the player who must shoot.
    const left = clockRemaining(state, now);
    if (left !== null && left <= URGENT_AT && left > 0 && isMyTurn(state)) {
      const second = Math.ceil(left);
      if (second !== lastTick) { lastTick = second; ticks += 1; audio.tick(); }
    } else lastTick = -1;
  }

  /**
   * The words over the table for what the pointer is doing now (or null).
   * @param {number} now
   * @param {import('../input.js').Situation} sit
   * @returns {{text: string, kind: string} | null}
   */
  function aimWords(now, sit) {
    if (now < feedback.until) return { text: feedback.text, kind: feedback.kind };
    if (!sit.myTurn) return null;
    if (aim.mode === 'pulling') {
      return aim.tooShort
        ? { text: 'Pull back to set the power…', kind: 'pull' }
        : { text: `Release to shoot · ${Math.round(aim.power * 100)} %`, kind: 'release' };
    }
    if (aim.mode === 'placing' && aim.placing) {
      if (!aim.placing.free) return { text: 'Not on another ball', kind: 'refused' };
      if (aim.placing.clamped && sit.ballInHand === 'behind_head_string') {
        return { text: 'Behind the head string only', kind: 'placing' };
      }
      return { text: 'Let go to put the cue ball here', kind: 'placing' };
    }
    if (sit.requiresCall && state.match?.called_pocket == null) {
      return { text: 'Tap the pocket you call for the 8', kind: 'call' };
    }
    if (sit.ballInHand) {
      return { text: sit.ballInHand === 'behind_head_string'
        ? 'Ball in hand behind the line: drag the white ball, or aim and shoot'
        : 'Ball in hand: drag the white ball anywhere, or aim and shoot', kind: 'hand' };
    }
    return null;
  }

  /** @type {{kind: string, end: [number, number]} | null} the object ball's guide, for tests */
  let objectGuide = null;

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
    const remote = !sit.myTurn && remoteCue && now - remoteCue.at < REMOTE_CUE_TTL
      && state.phase === 'aiming' ? remoteCue : null;
    const placing = aim.mode === 'placing' && aim.placing ? aim.placing : pendingCue ?? remote;
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
    objectGuide = null;
    if (state.phase === 'aiming' && cue && aim.mode !== 'placing' && !remote) {
      if (sit.myTurn) {
        const guide = aim.guide(table, sit.balls, cue, limits.cue_mass_ratio);
        const end = guideEnd(table, sit.balls, guide);
        drawGuide(ctx, view, table, cue, guide, end);
        drawCue(ctx, view, table, cue, aim.angle, aim.power);
        if (aim.mode === 'pulling') drawPowerMeter(ctx, view, cue, aim.power);
      } else if (state.aim && state.aim.seat !== state.me.seat
                 && now - state.aim.at < REMOTE_AIM_TTL) {
        const path = state.aim.angle + squirt(state.aim.tip[0] ?? 0, limits.cue_mass_ratio);
        const guide = castGuide(table, sit.balls, cue, path);
        drawGuide(ctx, view, table, cue, guide, guideEnd(table, sit.balls, guide));
        drawCue(ctx, view, table, cue, state.aim.angle, state.aim.power, 0.85);
        if (state.aim.power > 0) drawPowerMeter(ctx, view, cue, state.aim.power);
      }
    }
    if (sit.myTurn && state.phase === 'aiming') {
      hint.draw(ctx, view, table, sit.balls, sit.cue, limits);
    }
    if (sit.myTurn && sit.requiresCall) {
      drawPocketCall(ctx, view, table, state.match?.called_pocket ?? -1, aim.hoverPocket,
        0.5 + 0.5 * Math.sin(now * 4));
    } else if (state.match?.called_pocket != null && state.phase !== 'waiting') {
      drawPocketCall(ctx, view, table, state.match.called_pocket, -1, 0);
    }
    const left = clockRemaining(state, now);
    if (cue && left !== null && left <= URGENT_AT && state.phase === 'aiming') {
      drawClockRing(ctx, view, table, cue, left / URGENT_AT, 0.5 + 0.5 * Math.sin(now * 10));
    }
  }

  /**
   * Where the object ball's guide line ends: the rail, a ball or the pocket it drops in.
   * @param {any} table
   * @param {{id: number, x: number, y: number}[]} balls
   * @param {import('../geometry.js').Guide} guide
   * @returns {[number, number] | null}
   */
  function guideEnd(table, balls, guide) {
    if (guide.kind !== 'ball' || !guide.objectDir || guide.hitId === null) return null;
    const hit = balls.find((b) => b.id === guide.hitId);
    if (!hit) return null;
    const path = objectPath(table, balls, [hit.x, hit.y], guide.objectDir, [0, hit.id]);
    objectGuide = { kind: path.kind, end: path.end };
    return path.end;
  }

  /** @param {number} now */
  function renderOverlays(now) {
    const sit = situation();
    const words = aimWords(now, sit);
    const chip = $('aim-state');
    setText(chip, words?.text ?? '');
    chip.dataset.state = words?.kind ?? '';
    if (chip.hidden !== !words) chip.hidden = !words;
    const fine = $('fine-aim');
    const fineHidden = !(sit.myTurn && aim.mode !== 'placing' && !sit.requiresCall);
    if (fine.hidden !== fineHidden) fine.hidden = fineHidden;
    coach.show(sit.myTurn && aim.mode !== 'placing');
    hint.offer(sit.myTurn && state.room?.game === 'practice');
    const fb = $('frame-banner');
    const showFrame = now < frameBanner.until && state.phase !== 'over';
    if (showFrame) setText(fb, frameBanner.text);
    if (fb.hidden !== !showFrame) fb.hidden = !showFrame;
    // Ball in hand: the cue ball can be picked up where the pointer is over it.
    const cue = sit.cue;
    const overCue = !!(sit.myTurn && sit.ballInHand && cue && aim.pointer && state.table
      && Math.hypot(aim.pointer[0] - cue[0], aim.pointer[1] - cue[1])
        < state.table.ball_radius * 2.5);
    const cursor = aim.mode === 'placing' ? 'grabbing' : overCue ? 'grab' : '';
    if (canvas.style.cursor !== cursor) canvas.style.cursor = cursor;
    showSpin(shownTip(now));
    spinEl.classList.toggle('remote', shownTip(now) !== aim.tip);
  }

  startLoop((dt, now) => {
    update(dt, now);
    draw(now);
    renderHud(state, now);
    renderAway(state, now, graceAt);
    renderOverlays(now);
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
    get shotTime() { return playback.time; },
    get ready() { return !!(surface.view && surface.sprites); },
    /**
     * Table metres -> CSS pixels relative to the canvas's top-left corner.
     * @param {number} x
     * @param {number} y
     */
    toScreen(x, y) { return surface.view ? surface.view.toScreen(x, y) : null; },
    get aim() { return { angle: aim.angle, power: aim.power, mode: aim.mode, tip: aim.tip }; },
    get objectGuide() { return objectGuide; },
    get ticks() { return ticks; },
    get remoteCue() { return remoteCue; },
    get pendingCue() { return pendingCue; },
  };
}
