/**
 * A live table: the room's socket, the aim, and the shared table view (tableview.js), with
 * the display loop's two steps (javascript-tetris's `frame()`):
 *
 *  - in: `receive` reduces each server message into the state as it arrives and hands its
 *    effects to the shot playback; `update(dt, now)` plays the shot stream on, consumes the
 *    queued pointer input, and sends the throttled aim;
 *  - out: `draw(now)` paints the canvas (balls, aim, called pocket, clock ring) and the page
 *    round it (HUD, chat, the words over the table, the spin widget).
 */

import { RoomSocket, memory } from '../../net.js';
import {
  initialState, setConnection, isMyTurn, clockRemaining, playerName,
} from '../../state.js';
import { clampTip, tipAlongCue } from '../../geometry.js';
import { isPractice } from '../../balls.js';
import { attachPointer, AimController } from '../../input.js';
import {
  $, $input, applyInputLimits, renderHud, renderChat, renderDecision, renderAway, setText,
  URGENT_AT,
} from '../../ui.js';
import { Coach } from '../../coach.js';
import { ShotHint, powerFromSpeed } from '../../hint.js';
import { TableView } from '../../tableview.js';
import {
  drawHandArea, drawOwnAim, drawRemoteAim, drawCall, drawClock,
} from './aimlayer.js';
import { aimWords } from './words.js';
import { SpinWidget } from './spin.js';
import { elevationControl } from './elevation.js';
import { renderFrame, nominationAt } from './snooker.js';
import { CushionCounter, renderCarom, strikerBall } from './carom.js';

const AIM_INTERVAL = 0.1; // seconds between two `aim` messages (the server asks <= 20/s)
const REMOTE_AIM_TTL = 6; // seconds a relayed aim stays drawn without news
const REMOTE_CUE_TTL = 3; // seconds a relayed cue-ball drag stays drawn without news
const SHOT_ANSWER_WAIT = 3; // seconds without aiming after a shot is sent, awaiting the server
const FEEDBACK_FOR = 2.5; // seconds a "shot cancelled" / "drop refused" note stays up
const FRAME_BANNER_FOR = 3.5; // seconds the frame-won banner stays up
const TOUCH_LIFT = 44; // CSS px the dragged cue ball is drawn above a finger

/** @typedef {import('../../input.js').PointerAction} PointerAction */
/** @typedef {import('../../input.js').Situation} Situation */
/** @typedef {import('../../tableview.js').Frame} Frame */
/** @typedef {{x: number, y: number}} Point */

/** The local time in seconds, the loop's clock. */
const clock = () => performance.now() / 1000;

export class LiveTable {
  /** @param {string} roomId */
  constructor(roomId) {
    this.roomId = roomId;
    this.cushions = new CushionCounter(); // three-cushion: the striker's cushions this shot
    this.cushionsArmed = true;
    this.view = new TableView(/** @type {HTMLCanvasElement} */ ($('table')), $('table-wrap'),
      initialState({ roomId, name: memory.name() }));
    this.audio = this.view.audio;
    this.playback = this.view.playback;
    this.aim = new AimController();
    this.coach = new Coach($('coach'), $('coach-ok'));
    this.hint = new ShotHint(/** @type {HTMLButtonElement} */ ($('hint')), $('hint-text'),
      roomId, () => this.seatToken(), () => this.limits.max_speed,
      /** @type {HTMLButtonElement} */ ($('hint-try')), (plan) => this.tryPlan(plan));
    /** @type {number | null} the power a tried hint set, for its Shoot button */
    this.triedPower = null;
    $('hint-shoot').addEventListener('click', () => this.shootTried());
    /** @type {PointerAction[]} */
    this.inputQueue = [];
    /** @type {Point | null} where we asked to place the cue ball */
    this.pendingCue = null;
    this.shotSentAt = -Infinity; // a shot was sent: no more aiming until the server answers
    this.lastAimSent = -Infinity;
    this.lastCueSent = '';
    this.shotsSeen = 0;
    this.graceAt = 0; // local time the grace list came
    /** @type {{x: number, y: number, seat: number, at: number} | null} another's cue-ball drag */
    this.remoteCue = null;
    this.feedbackSeq = 0;
    /** @type {{text: string, kind: string, until: number}} */
    this.feedback = { text: '', kind: '', until: 0 };
    /** @type {{text: string, until: number}} */
    this.frameBanner = { text: '', until: 0 };
    this.lastTick = -1;
    this.ticks = 0; // clock ticks played (the shot clock's last seconds)
    /** @type {import('./aimlayer.js').ObjectGuide | null} the object ball's guide, for tests */
    this.objectGuide = null;
    this.limits = this.state.limits;
    applyInputLimits(this.limits);
    this.keepSpin = keepSpinBox();
    this.spin = new SpinWidget($('spin'), () => this.limits.max_tip, (tip) => {
      this.aim.tip = tip;
      this.aim.dirty = true;
    });
    this.elevation = elevationControl((radians) => {
      this.aim.elevation = Math.min(radians, this.limits.max_elevation);
      this.aim.dirty = true;
    });
    this.socket = new RoomSocket(roomId, () => this.seatToken(), {
      onMessage: (msg) => this.receive(msg),
      onStatus: (status, detail) => {
        this.state = setConnection(this.state, status);
        if (detail && status === 'closed') this.state = { ...this.state, outcome: detail };
      },
    });
    attachPointer(this.view.canvas, this.inputQueue);
  }

  get state() { return this.view.state; }
  set state(s) { this.view.state = s; }

  seatToken() { return memory.seat(this.roomId)?.token ?? null; }

  /** @param {Record<string, any>} msg */
  send(msg) { return this.socket.send(msg); }

  /** The game (frame) of the match now: what a concession or a decision is meant for. */
  currentGame() { return (this.state.match?.games_played ?? 0) + 1; }

  /**
   * Fine aim, while it is this player's turn to aim.
   * @param {number} delta radians
   */
  nudge(delta) {
    if (this.situation().myTurn && this.aim.mode !== 'placing') this.aim.nudge(delta);
  }

  /**
   * "Try it": the table set up as the hint has it (the cue ball placed, the aim, spin and
   * power set), for the player to shoot with one press or to adjust first.
   * @param {import('../../hint.js').Hint} plan
   */
  tryPlan(plan) {
    if (!this.situation().myTurn) return;
    if (plan.place) {
      const [x, y] = plan.place;
      this.pendingCue = { x, y };
      this.send({ type: 'place_cue', x, y });
    }
    this.aim.reset();
    this.aim.angle = plan.angle;
    // A jump's tip comes as the server names it: the spin widget shows it along the cue.
    const elevation = plan.elevation ?? 0;
    const tip = tipAlongCue(plan.tip[0], plan.tip[1], elevation);
    this.aim.tip = clampTip(tip[0], tip[1], this.limits.max_tip);
    this.elevation.set(Math.round((elevation * 180) / Math.PI));
    this.aim.power = powerFromSpeed(plan.speed, this.limits.max_speed);
    this.aim.dirty = true;
    this.triedPower = this.aim.power;
  }

  /** The Shoot button of a tried hint: the aim as it is now, at the hint's power. */
  shootTried() {
    if (this.triedPower === null || !this.situation().myTurn) return;
    this.aim.power = this.triedPower;
    const shot = this.aim.shot(this.limits);
    this.triedPower = null;
    if (!this.send(shot)) return;
    this.shotSentAt = clock();
    this.aim.dirty = false;
    this.coach.done();
  }

  // ---- in: messages ---------------------------------------------------------------------

  /** @param {Record<string, any>} msg */
  receive(msg) {
    const now = clock();
    const before = this.state;
    const effects = this.view.receive(msg, now);
    this.note(msg, before, now);
    this.playback.setTable(this.state.table);
    if (this.state.limits !== this.limits) {
      this.limits = this.state.limits;
      applyInputLimits(this.limits);
      this.aim.tip = clampTip(this.aim.tip[0], this.aim.tip[1], this.limits.max_tip);
    }
    for (const e of effects) this.carryOut(e, now);
    this.view.play(effects, now);
  }

  /**
   * What a message means for this page beyond the shared state.
   * @param {Record<string, any>} msg
   * @param {import('../../state.js').RoomState} before the state before it
   * @param {number} now
   */
  note(msg, before, now) {
    if (msg.type === 'error') this.refused(msg.ref);
    if (msg.type === 'state' || msg.type === 'presence') this.graceAt = now;
    if (msg.type === 'aim') {
      this.remoteCue = Array.isArray(msg.cue)
        ? { x: msg.cue[0], y: msg.cue[1], seat: msg.seat, at: now } : null;
    }
    if (msg.type !== 'state') return;
    if (Array.isArray(msg.chat)) {
      // The room's last lines (sent on connecting): a reload keeps the conversation.
      this.state = { ...this.state, chat: msg.chat.map((/** @type {any} */ c) =>
        ({ seat: c.seat, name: c.name, text: c.text })) };
    }
    if (this.state.phase !== 'aiming') this.remoteCue = null;
    if (before.phase === 'over' && this.state.phase === 'aiming') {
      // A rematch began: last match's words are history.
      this.state = { ...this.state, outcome: '' };
      this.frameBanner = { text: '', until: 0 };
    }
  }

  /**
   * The server refused what this page sent (`ref`): take back what waited for it.
   * @param {string | undefined} ref
   */
  refused(ref) {
    if (ref === 'place_cue') this.pendingCue = null;
    if (ref === 'shoot') this.shotSentAt = -Infinity;
    if (ref === 'aim') this.state = { ...this.state, error: null };
  }

  /**
   * One of the reducer's effects, this page's part (the playback does the rest).
   * @param {import('../../state.js').Effect} e
   * @param {number} now
   */
  carryOut(e, now) {
    switch (e.kind) {
      case 'sync': this.send({ type: 'sync' }); break;
      case 'rest':
        this.pendingCue = null;
        this.shotSentAt = -Infinity;
        break;
      case 'motion': this.shotStarts(); break;
      case 'result': this.frameWon(e.result, now); break;
      default: break;
    }
  }

  /** A shot starts (or, joining, goes on) on this page: the aim waits for the next one. */
  shotStarts() {
    this.shotsSeen += 1;
    this.hint.clear();
    this.triedPower = null;
    this.shotSentAt = -Infinity;
    this.aim.reset();
    this.remoteCue = null;
    // The last shot's words go stale as the next one is played.
    this.state = { ...this.state, outcome: '' };
    if (!this.keepSpin.checked) {
      this.aim.tip = [0, 0];
      this.elevation.set(0);
    }
  }

  /**
   * A frame won (the match going on): the banner saying who won it, with the score.
   * @param {any} result the `shot_result` message
   * @param {number} now
   */
  frameWon(result, now) {
    const o = result?.outcome;
    if (!o?.frame_over || o.winner == null || result.match_over) return;
    const score = Array.isArray(result.score) ? ` · ${result.score.join(' – ')}` : '';
    this.frameBanner = { text: `${playerName(this.state, o.winner) ?? 'A player'} wins the frame`
      + score, until: now + FRAME_BANNER_FOR };
  }

  // ---- in: the loop's update ------------------------------------------------------------

  /** @returns {Situation} */
  situation() {
    const { state, playback } = this;
    // Carom: the striker's own ball is the cue ball (id 0 in what is aimed and guided).
    const striker = strikerBall(state);
    const asAimed = (/** @type {number} */ id) => (id === striker ? 0 : id === 0 ? striker : id);
    const ballList = [...playback.balls].map(([id, b]) => ({ id: asAimed(id), x: b.x, y: b.y }));
    const cueBall = playback.balls.get(striker);
    /** @type {[number, number] | null} */
    const cue = this.pendingCue ? [this.pendingCue.x, this.pendingCue.y]
      : cueBall ? [cueBall.x, cueBall.y] : null;
    const m = state.match;
    return {
      table: state.table,
      balls: ballList,
      cue,
      myTurn: isMyTurn(state) && state.phase === 'aiming' && !m?.decision
        && clock() - this.shotSentAt > SHOT_ANSWER_WAIT,
      ballInHand: m?.ball_in_hand ?? null,
      requiresCall: !!m?.requires_call,
      limits: this.limits,
    };
  }

  /**
   * @param {number} dt
   * @param {number} now
   */
  update(dt, now) {
    this.view.update(dt, now);
    const sit = this.situation();
    while (this.inputQueue.length) {
      this.handle(/** @type {PointerAction} */ (this.inputQueue.shift()), sit, now);
    }
    const { aim } = this;
    if (aim.feedback.seq !== this.feedbackSeq) {
      this.feedbackSeq = aim.feedback.seq;
      this.feedback = { text: aim.feedback.text, kind: aim.feedback.kind,
        until: now + FEEDBACK_FOR };
    }
    if (!sit.myTurn && aim.mode !== 'idle') aim.reset();
    if (sit.myTurn) this.sendAim(now);
    this.tickClock(now);
  }

  /**
   * One pointer action: into table metres, through the aim, its messages sent.
   * @param {PointerAction} a
   * @param {Situation} sit
   * @param {number} now
   */
  handle(a, sit, now) {
    const { view } = this.view.surface;
    if (a.sx !== undefined && a.sy !== undefined && view) {
      // A cue ball dragged by a finger is held above it, where the player can see it.
      const lift = a.pointerType === 'touch' && this.aim.mode === 'placing' && a.type !== 'down'
        ? TOUCH_LIFT : 0;
      [a.x, a.y] = view.toTable(a.sx, a.sy - lift);
    }
    if (a.type === 'down' && this.nominateAt(a, sit)) return;
    for (const msg of this.aim.handle(a, sit)) {
      if (msg.type === 'place_cue') this.pendingCue = { x: msg.x, y: msg.y };
      if (msg.type === 'shoot') { this.shotSentAt = now; this.aim.dirty = false; this.coach.done(); }
      this.send(msg);
    }
  }

  /**
   * Snooker: a tap on a ball that may be nominated (a colour on, a free ball) nominates it
   * instead of starting an aim; true when it did.
   * @param {PointerAction} a
   * @param {Situation} sit
   */
  nominateAt(a, sit) {
    const choices = /** @type {number[]} */ (/** @type {any} */ (this.state.match)?.nominations ?? []);
    if (!sit.myTurn || !choices.length || a.x === undefined || a.y === undefined) return false;
    const ball = nominationAt(sit.balls, choices, sit.table?.ball_radius ?? 0.026, a.x, a.y);
    if (ball === null) return false;
    this.send({ type: 'nominate', ball });
    return true;
  }

  /**
   * The shooter's aim (and dragged cue ball) for the others, at most every AIM_INTERVAL.
   * @param {number} now
   */
  sendAim(now) {
    const { aim } = this;
    const dragged = aim.mode === 'placing' && aim.placing
      ? `${aim.placing.x.toFixed(3)},${aim.placing.y.toFixed(3)}` : '';
    if (dragged !== this.lastCueSent) aim.dirty = true;
    if (!aim.dirty || now - this.lastAimSent < AIM_INTERVAL) return;
    aim.dirty = false;
    this.lastAimSent = now;
    this.lastCueSent = dragged;
    /** @type {Record<string, any>} */
    const msg = { type: 'aim', angle: Math.round(aim.angle * 1e4) / 1e4,
      power: Math.round(aim.power * 1000) / 1000, tip: aim.tip };
    const raised = aim.elevation > 0 ? aim.shot(this.limits) : null;
    if (raised?.elevation) {
      // A raised cue: the tip as `shoot` names it, so the others' guides curve as ours.
      msg.tip = raised.tip;
      msg.elevation = raised.elevation;
    }
    if (aim.mode === 'placing' && aim.placing) {
      msg.cue = [Math.round(aim.placing.x * 1e4) / 1e4, Math.round(aim.placing.y * 1e4) / 1e4];
    }
    this.send(msg);
  }

  /**
   * The shot clock's last seconds tick for the player who must shoot.
   * @param {number} now
   */
  tickClock(now) {
    const left = clockRemaining(this.state, now);
    if (left !== null && left <= URGENT_AT && left > 0 && isMyTurn(this.state)) {
      const second = Math.ceil(left);
      if (second !== this.lastTick) { this.lastTick = second; this.ticks += 1; this.audio.tick(); }
    } else this.lastTick = -1;
  }

  // ---- out: the loop's draw -------------------------------------------------------------

  /** @param {number} now */
  draw(now) {
    this.drawTable(now);
    const { state } = this;
    renderHud(state, now);
    renderAway(state, now, this.graceAt);
    this.drawOverlays(now);
    renderChat(state);
    renderDecision(state, (option) => this.send({ type: 'decide', option,
      game: this.currentGame() }));
    renderFrame(state, (ball) => this.send({ type: 'nominate', ball }));
    renderCarom(state, this.cushions);
  }

  /**
   * Three-cushion: count the cushions the striker's ball meets while a shot rolls.
   * @param {Situation} sit
   */
  countCushions(sit) {
    const { state } = this;
    if (!state.table || !/** @type {any} */ (state.match)?.carom) return;
    if (state.phase !== 'rolling') { this.cushionsArmed = true; return; }
    if (this.cushionsArmed) { this.cushions.reset(); this.cushionsArmed = false; }
    const ball = sit.balls.find((b) => b.id === 0);
    if (ball) this.cushions.update(state.table, ball.x, ball.y);
  }

  /** @param {number} now */
  drawTable(now) {
    const { state, aim } = this;
    const frame = this.view.begin(state.table);
    if (!frame) return;
    const sit = this.situation();
    this.countCushions(sit);
    const dragging = aim.mode === 'placing' && aim.placing ? aim.placing : null;
    if (sit.myTurn) drawHandArea(frame, state.table, sit.ballInHand, dragging);
    const remote = this.remoteDrag(sit, now);
    const placing = dragging ?? this.pendingCue ?? remote;
    this.view.drawBalls(frame, now, placing ? this.cueBallAt(placing) : undefined);
    /** @type {[number, number] | null} */
    const cue = placing ? [placing.x, placing.y] : sit.cue;
    this.objectGuide = null;
    if (state.phase === 'aiming' && cue && aim.mode !== 'placing' && !remote) {
      this.objectGuide = this.drawAim(frame, sit, cue, now);
    }
    this.drawMarks(frame, sit, cue, now);
  }

  /**
   * Another player's cue-ball drag, while it is fresh and they are at the table.
   * @param {Situation} sit
   * @param {number} now
   */
  remoteDrag(sit, now) {
    const drag = this.remoteCue;
    if (sit.myTurn || !drag || now - drag.at >= REMOTE_CUE_TTL) return null;
    return this.state.phase === 'aiming' ? drag : null;
  }

  /**
   * Over the balls and the aim: the practice hint, the pocket called for the 8 and the
   * shot clock's ring.
   * @param {Frame} frame
   * @param {Situation} sit
   * @param {[number, number] | null} cue
   * @param {number} now
   */
  drawMarks(frame, sit, cue, now) {
    const { state } = this;
    const table = state.table;
    if (sit.myTurn && state.phase === 'aiming') {
      this.hint.draw(frame.ctx, frame.view, table, sit.balls, sit.cue, this.limits);
    }
    const choosing = sit.myTurn && sit.requiresCall;
    if (choosing || state.phase !== 'waiting') {
      drawCall(frame, table, { choosing, called: state.match?.called_pocket ?? null,
        hover: this.aim.hoverPocket }, now);
    }
    if (cue && state.phase === 'aiming') drawClock(frame, table, cue, clockRemaining(state, now), now);
  }

  /**
   * The balls with the cue ball moved to `p` (dragged, asked for, or another's drag).
   * @param {Point} p
   */
  cueBallAt(p) {
    const shown = new Map(this.playback.balls);
    const cueBall = shown.get(0) ?? { cel: 0, heading: 0, speed: 0 };
    shown.set(0, { ...cueBall, x: p.x, y: p.y });
    return shown;
  }

  /**
   * The aim drawn from `cue`: the shooter's own, or the relayed one of the player at the
   * table while it is fresh.
   * @param {Frame} frame
   * @param {Situation} sit
   * @param {[number, number]} cue
   * @param {number} now
   */
  drawAim(frame, sit, cue, now) {
    const { state } = this;
    if (sit.myTurn) return drawOwnAim(frame, state.table, sit.balls, cue, this.aim, this.limits);
    const remote = state.aim;
    if (remote && remote.seat !== state.me.seat && now - remote.at < REMOTE_AIM_TTL) {
      return drawRemoteAim(frame, state.table, sit.balls, cue, remote, this.limits);
    }
    return null;
  }

  /**
   * The page round the canvas that follows the aim: the words over the table, fine aim,
   * the coach, the hint, the frame banner, the cursor, the spin.
   * @param {number} now
   */
  drawOverlays(now) {
    const { state, aim } = this;
    const sit = this.situation();
    const words = aimWords({ feedback: this.feedback, aim, sit,
      called: state.match?.called_pocket, time: now });
    const chip = $('aim-state');
    setText(chip, words?.text ?? '');
    chip.dataset.state = words?.kind ?? '';
    setHidden(chip, !words);
    setHidden($('fine-aim'), !(sit.myTurn && aim.mode !== 'placing' && !sit.requiresCall));
    this.coach.show(sit.myTurn && aim.mode !== 'placing');
    this.hint.offer(sit.myTurn && isPractice(state.room?.game));
    const shoot = $('hint-shoot');
    const tried = this.triedPower !== null && this.hint.plan !== null && sit.myTurn
      && aim.mode === 'idle';
    setHidden(shoot, !tried);
    if (tried) setText(shoot, `Shoot · ${Math.round(/** @type {number} */ (this.triedPower) * 100)} %`);
    const banner = $('frame-banner');
    const showFrame = now < this.frameBanner.until && state.phase !== 'over';
    if (showFrame) setText(banner, this.frameBanner.text);
    setHidden(banner, !showFrame);
    const canvas = this.view.canvas;
    const cursor = aim.mode === 'placing' ? 'grabbing' : this.overCueBall(sit) ? 'grab' : '';
    if (canvas.style.cursor !== cursor) canvas.style.cursor = cursor;
    this.showCue(sit, now);
  }

  /**
   * The spin widget and the elevation's side view: the shooter's own, or the relayed ones
   * of the player at the table (their tip seen along their raised cue).
   * @param {Situation} sit
   * @param {number} now
   */
  showCue(sit, now) {
    const shown = this.shownTip(sit, now);
    const remote = shown !== this.aim.tip;
    const raised = remote ? this.state.aim?.elevation ?? 0 : 0;
    const tip = remote ? tipAlongCue(shown[0], shown[1], raised) : shown;
    this.spin.show(tip, remote);
    this.elevation.show(tip[1], remote ? Math.round((raised * 180) / Math.PI) : null);
  }

  /**
   * Ball in hand: the cue ball can be picked up where the pointer is over it.
   * @param {Situation} sit
   */
  overCueBall(sit) {
    const { cue } = sit;
    const { pointer } = this.aim;
    if (!sit.myTurn || !sit.ballInHand || !cue || !pointer || !this.state.table) return false;
    return Math.hypot(pointer[0] - cue[0], pointer[1] - cue[1])
      < this.state.table.ball_radius * 2.5;
  }

  /**
   * The spin shown: the shooter's own, or the relayed spin of the player at the table.
   * @param {Situation} sit
   * @param {number} now
   * @returns {number[]}
   */
  shownTip(sit, now) {
    const { state } = this;
    if (sit.myTurn || !state.aim || state.aim.seat === state.me.seat
        || now - state.aim.at > REMOTE_AIM_TTL || state.phase !== 'aiming') return this.aim.tip;
    return state.aim.tip;
  }
}

/** The "keep spin" box: remembered; unticked, the spin goes back to centre after a shot. */
function keepSpinBox() {
  const box = $input('keep-spin');
  box.checked = localStorage.getItem('pool.keepSpin') === '1';
  box.addEventListener('change', () => {
    localStorage.setItem('pool.keepSpin', box.checked ? '1' : '0');
  });
  return box;
}

/**
 * @param {HTMLElement} el
 * @param {boolean} hidden
 */
function setHidden(el, hidden) {
  if (el.hidden !== hidden) el.hidden = hidden;
}
