/**
 * Pointer input on the table (mouse, pen and touch through pointer events).
 *
 * `attachPointer` only queues actions (javascript-tetris's habit); the game loop hands them
 * to `AimController.handle`, which turns them into aiming state and commands to send.
 * The controller is pure (no DOM): actions carry table coordinates.
 *
 * Gestures: move the pointer to aim (the cue follows it around the cue ball); press where
 * you aim, pull back along the line to set the power, release to shoot (release without
 * pulling cancels). With ball in hand, drag the cue ball. When the 8 must be called, click a
 * pocket.
 */

import {
  castGuide, squirt, pullPower, speedFromPower, placeCue, placementArea, pocketAt, dist, clampTip,
  tipSeenLevel,
} from './geometry.js';
import { curvedGuide } from './swerve.js';

/**
 * @typedef {object} PointerAction
 * @property {'down'|'move'|'up'|'cancel'} type
 * @property {number} [sx] CSS pixels on the canvas
 * @property {number} [sy]
 * @property {number} [x] table metres (filled in by the loop from sx, sy)
 * @property {number} [y]
 * @property {string} [pointerType]
 */

/**
 * What the controller needs to know about the table at the moment of an action.
 * @typedef {object} Situation
 * @property {any} table the server's table geometry (null before the first state)
 * @property {{id: number, x: number, y: number}[]} balls
 * @property {[number, number] | null} cue
 * @property {boolean} myTurn
 * @property {string | null} ballInHand
 * @property {boolean} requiresCall
 * @property {import('./limits.js').Limits} limits the server's limits
 */

/**
 * Queue pointer actions from `canvas` as {type, sx, sy, pointerType} (CSS pixels).
 * @param {HTMLCanvasElement} canvas
 * @param {PointerAction[]} queue
 */
export function attachPointer(canvas, queue) {
  /** @param {PointerEvent} ev */
  const pos = (ev) => {
    const r = canvas.getBoundingClientRect();
    return { sx: ev.clientX - r.left, sy: ev.clientY - r.top, pointerType: ev.pointerType };
  };
  canvas.addEventListener('pointerdown', (ev) => {
    if (ev.button !== undefined && ev.button > 0) return;
    canvas.setPointerCapture?.(ev.pointerId);
    queue.push({ type: 'down', ...pos(ev) });
    ev.preventDefault();
  });
  canvas.addEventListener('pointermove', (ev) => queue.push({ type: 'move', ...pos(ev) }));
  canvas.addEventListener('pointerup', (ev) => queue.push({ type: 'up', ...pos(ev) }));
  canvas.addEventListener('pointercancel', () => queue.push({ type: 'cancel' }));
  canvas.addEventListener('contextmenu', (ev) => ev.preventDefault());
}

/** How far (metres on the table) a full pull-back is. */
export const MAX_PULL = 0.4;
/** Below this power a release is a cancel. */
export const MIN_POWER = 0.03;
/** The power a raised cue's curved guide is drawn for until the player pulls back. */
export const GUIDE_POWER = 0.35;

/**
 * What the player is told after an action that did nothing on purpose (a cancelled shot,
 * a refused drop of the cue ball). `seq` grows with each one, so the shell shows it once.
 * @typedef {{seq: number, kind: 'cancelled' | 'refused', text: string}} Feedback
 */

export class AimController {
  constructor() {
    this.angle = 0; // radians, table frame
    this.power = 0;
    /** @type {[number, number]} where the tip strikes, seen along the cue */
    this.tip = [0, 0];
    this.elevation = 0; // the cue's angle above the bed, radians
    /** @type {'idle'|'pulling'|'placing'} */
    this.mode = 'idle';
    /** @type {[number, number] | null} */
    this.anchor = null;
    /** @type {[number, number] | null} last pointer position (table metres) */
    this.pointer = null;
    /** @type {{x: number, y: number, free: boolean, clamped?: boolean} | null} wished cue-ball
     *  place while dragging */
    this.placing = null;
    this.hoverPocket = -1;
    this.dirty = false; // aim changed since the last `aim` message
    /** @type {Feedback} */
    this.feedback = { seq: 0, kind: 'cancelled', text: '' };
  }

  /**
   * @param {Feedback['kind']} kind
   * @param {string} text
   */
  tell(kind, text) {
    this.feedback = { seq: this.feedback.seq + 1, kind, text };
  }

  /**
   * Fine aim: turn the cue by `delta` radians (buttons, arrow keys, the mouse wheel).
   * @param {number} delta
   */
  nudge(delta) {
    this.angle = Math.atan2(Math.sin(this.angle + delta), Math.cos(this.angle + delta));
    this.dirty = true;
  }

  /** True while a press has not been pulled back far enough to shoot on release. */
  get tooShort() {
    return this.mode === 'pulling' && this.power < MIN_POWER;
  }

  reset() {
    this.mode = 'idle';
    this.power = 0;
    this.anchor = null;
    this.placing = null;
  }

  /**
   * Handle one action {type, x, y} (table metres) given the situation. Returns the
   * messages to send (protocol objects).
   * @param {PointerAction} action
   * @param {Situation} ctx
   * @returns {Record<string, any>[]}
   */
  handle(action, ctx) {
    if (action.type === 'cancel') {
      if (this.mode === 'pulling') this.tell('cancelled', 'Shot cancelled.');
      this.reset();
      this.dirty = true;
      return [];
    }
    /** @type {[number, number] | null} */
    const p = action.x === undefined || action.y === undefined ? this.pointer
      : [action.x, action.y];
    if (p) this.pointer = p;
    if (!ctx.myTurn || !ctx.table) { this.reset(); return []; }
    this.hoverPocket = ctx.requiresCall && p ? pocketAt(ctx.table, p[0], p[1]) : -1;
    if (action.type === 'down') return p ? this.press(p, ctx) : [];
    if (action.type === 'move') { if (p) this.move(p, action, ctx); return []; }
    if (action.type === 'up') return this.release(p, ctx);
    return [];
  }

  /**
   * A press at `p`: call the pocket under it, pick up the cue ball (ball in hand), or start
   * pulling back from where the cue points.
   * @param {[number, number]} p
   * @param {Situation} ctx
   * @returns {Record<string, any>[]}
   */
  press(p, ctx) {
    const { table } = ctx;
    const r = table.ball_radius;
    if (ctx.requiresCall && this.hoverPocket >= 0) return [{ type: 'call', pocket: this.hoverPocket }];
    const area = placementArea(table, ctx.ballInHand);
    if (area && (!ctx.cue || dist(p[0], p[1], ctx.cue[0], ctx.cue[1]) < r * 2.5)) {
      this.mode = 'placing';
      this.placing = placeCue(table, area, ctx.balls, p[0], p[1]);
      return [];
    }
    if (!ctx.cue) return [];
    this.mode = 'pulling';
    this.anchor = p;
    if (dist(p[0], p[1], ctx.cue[0], ctx.cue[1]) > r) {
      this.angle = Math.atan2(p[1] - ctx.cue[1], p[0] - ctx.cue[0]);
    }
    this.power = 0;
    this.dirty = true;
    return [];
  }

  /**
   * A move to `p`: drag the cue ball, set the power while pulling, or aim (not by touch:
   * a finger aims by pressing).
   * @param {[number, number]} p
   * @param {PointerAction} action
   * @param {Situation} ctx
   */
  move(p, action, ctx) {
    const { table } = ctx;
    const area = placementArea(table, ctx.ballInHand);
    if (this.mode === 'placing' && area) {
      this.placing = placeCue(table, area, ctx.balls, p[0], p[1]);
    } else if (this.mode === 'pulling' && this.anchor) {
      this.power = pullPower(this.anchor, p, this.angle, MAX_PULL);
      this.dirty = true;
    } else if (ctx.cue && action.pointerType !== 'touch'
               && dist(p[0], p[1], ctx.cue[0], ctx.cue[1]) > table.ball_radius) {
      this.angle = Math.atan2(p[1] - ctx.cue[1], p[0] - ctx.cue[0]);
      this.dirty = true;
    }
  }

  /**
   * A release: drop the dragged cue ball, or shoot (a release without pulling cancels).
   * @param {[number, number] | null} p
   * @param {Situation} ctx
   * @returns {Record<string, any>[]}
   */
  release(p, ctx) {
    if (this.mode === 'placing' && this.placing) {
      const { placing } = this;
      this.mode = 'idle';
      this.placing = null;
      if (placing.free) return [{ type: 'place_cue', x: round6(placing.x), y: round6(placing.y) }];
      this.tell('refused', 'The cue ball cannot go on another ball: drop it on free cloth.');
      return [];
    }
    if (this.mode !== 'pulling') return [];
    if (p && this.anchor) this.power = pullPower(this.anchor, p, this.angle, MAX_PULL);
    /** @type {Record<string, any>[]} */
    const out = [];
    if (this.power < MIN_POWER) {
      this.tell('cancelled', 'Shot cancelled: keep pressing and pull back, then let go.');
    } else {
      out.push(this.shot(ctx.limits));
    }
    this.reset();
    this.dirty = true;
    return out;
  }

  /**
   * The `shoot` message for the aim now, within the server's limits.
   * @param {import('./limits.js').Limits} limits
   * @param {number} [power] the power to shoot at (the pulled one unless given)
   * @returns {{type: string, angle: number, speed: number, tip: number[], elevation?: number}}
   */
  shot(limits, power = this.power) {
    const { max_speed: maxSpeed, max_tip: maxTip } = limits;
    const tip = clampTip(this.tip[0], this.tip[1], maxTip);
    const rounded = tip.map(round6);
    const level = Math.hypot(rounded[0], rounded[1]) <= maxTip ? rounded : tip.map(trunc6);
    const out = { type: 'shoot', angle: round6(this.angle),
      speed: Math.min(maxSpeed, round6(speedFromPower(power, maxSpeed))), tip: level };
    const elevation = Math.min(Math.max(trunc6(this.elevation), 0), limits.max_elevation);
    if (elevation > 0) {
      // A raised cue: the server names the tip as seen from behind at the bed's level (a
      // hair inside the miscue limit, so the rounding cannot carry it over).
      const [side, height] = tipSeenLevel(level[0] * 0.999, level[1] * 0.999, elevation);
      return { ...out, tip: [trunc6(side), trunc6(height)], elevation };
    }
    return out;
  }

  /**
   * The guide for the current aim from `cue`: along the path side spin squirts it to, and
   * with a raised cue along the curve the engine's sliding friction gives it (swerve,
   * massé: `curvedGuide`). The curve depends on the speed: the power pulled, else
   * GUIDE_POWER until the player pulls back.
   * @param {any} table
   * @param {{id: number, x: number, y: number}[]} balls
   * @param {[number, number]} cue
   * @param {import('./limits.js').Limits} limits the server's limits
   * @returns {import('./swerve.js').CurvedGuide}
   */
  guide(table, balls, cue, limits) {
    if (this.elevation <= 0) {
      const angle = this.angle + squirt(this.tip[0], limits.cue_mass_ratio);
      return { bends: [], from: cue, guide: castGuide(table, balls, cue, angle) };
    }
    const power = this.power >= MIN_POWER ? this.power : GUIDE_POWER;
    const stroke = this.shot(limits, power);
    return curvedGuide(table, balls, cue, { ...stroke, elevation: stroke.elevation ?? 0 },
      limits.cue_mass_ratio);
  }
}

/** @param {number} v */
function round6(v) {
  return Math.round(v * 1e6) / 1e6;
}

/**
 * Towards zero: rounding a tip clamped onto the edge of the legal disc can carry it just
 * outside, which the server refuses.
 * @param {number} v
 */
function trunc6(v) {
  return Math.trunc(v * 1e6) / 1e6;
}
