/**
 * "Show me a shot" on a practice table: the strongest computer level plans the player's
 * shot on the server (`POST /api/rooms/{room_id}/hint`, docs/protocol.md) and its plan is
 * drawn over the table without being played: where it would put the cue ball, the aim line
 * to the ghost ball and the object ball's path, the cue drawn back by the power, and a
 * caption with the power (in % like the aim's own) and the spin. "Try it" hands the plan to
 * the table, which sets the aim, spin and power and places the cue ball: the player only
 * has to shoot, or adjust first. The plan stays until the balls move.
 */

import { request } from './net.js';
import { castGuide, objectPath, squirt, MIN_SPEED } from './geometry.js';
import { drawCue, drawGuide } from './render.js';

/**
 * @typedef {{level: string, kind: string, place: [number, number] | null,
 *   call: number | null, angle: number, speed: number, tip: [number, number],
 *   target: number | null, pocket: number | null, chance: number | null,
 *   via?: string | null, elevation?: number}} Hint
 */

const SPIN_WORDS = 0.08; // a tip offset (fraction of the radius) below this is "centre"

/**
 * The power in [0, 1] that gives `speed` (the inverse of geometry.js `speedFromPower`).
 * @param {number} speed
 * @param {number} maxSpeed
 */
export function powerFromSpeed(speed, maxSpeed) {
  const top = Math.max(MIN_SPEED, maxSpeed);
  if (top <= MIN_SPEED) return 1;
  const p = Math.min(1, Math.max(0, (speed - MIN_SPEED) / (top - MIN_SPEED)));
  return p ** (1 / 1.6);
}

/**
 * The spin of a tip offset (side, height) in words.
 * @param {[number, number]} tip
 */
export function spinWords(tip) {
  const [side, height] = tip;
  const words = [];
  if (height > SPIN_WORDS) words.push('follow');
  else if (height < -SPIN_WORDS) words.push('draw');
  if (side > SPIN_WORDS) words.push('right side');
  else if (side < -SPIN_WORDS) words.push('left side');
  return words.length ? words.join(' and ') : 'centre ball';
}

/**
 * One line saying what the plan is.
 * @param {Hint} hint
 * @param {number} maxSpeed the server's `max_speed`: the power's 100 %
 */
export function describeHint(hint, maxSpeed) {
  let what = 'Play safe';
  if (hint.kind === 'pot' && hint.target !== null) {
    what = `Pot the ${hint.target}`;
    if (hint.via === 'bank') what = `Bank the ${hint.target} off a cushion`;
    else if (hint.via === 'combo') what = `Pot the ${hint.target} in a combination`;
    else if (hint.via === 'carom') what = `Carom the ${hint.target} off another ball`;
    else if (hint.via === 'billiard') what = `Glance the cue ball off the first ball into the ${hint.target}`;
  }
  else if (hint.kind === 'kick') what = 'Kick at it off a cushion';
  else if (hint.kind === 'point') what = 'Score the point';
  else if (hint.kind === 'break') what = 'Break';
  const odds = hint.kind === 'pot' && hint.chance !== null
    ? ` (${Math.round(hint.chance * 100)} % of the computer's trials went in)`
    : hint.kind === 'point' && hint.chance !== null
      ? ` (${Math.round(hint.chance * 100)} % of the computer's trials scored)` : '';
  const power = Math.round(powerFromSpeed(hint.speed, maxSpeed) * 100);
  return `${what}${odds}: power ${power} %, ${spinWords(hint.tip)}.`;
}

/** The button, its caption and the plan on show. */
export class ShotHint {
  /**
   * @param {HTMLButtonElement} button
   * @param {HTMLElement} caption
   * @param {string} roomId
   * @param {() => string | null} token the seat's token
   * @param {() => number} maxSpeed the server's `max_speed` now
   * @param {HTMLButtonElement} tryButton "Try it"
   * @param {(plan: Hint) => void} onTry set the table up as the plan has it
   */
  constructor(button, caption, roomId, token, maxSpeed, tryButton, onTry) {
    this.button = button;
    this.caption = caption;
    this.roomId = roomId;
    this.token = token;
    this.maxSpeed = maxSpeed;
    this.tryButton = tryButton;
    tryButton.addEventListener('click', () => { if (this.plan) onTry(this.plan); });
    /** @type {Hint | null} */
    this.plan = null;
    this.asking = false;
    button.addEventListener('click', () => { this.ask(); });
  }

  /**
   * Show the button when a hint can be asked for (a practice table, the player's shot).
   * @param {boolean} available
   */
  offer(available) {
    if (this.button.hidden === available) this.button.hidden = !available;
    if (!available && this.plan) this.clear();
  }

  async ask() {
    const token = this.token();
    if (!token || this.asking) return;
    this.asking = true;
    this.button.disabled = true;
    this.caption.hidden = false;
    this.caption.textContent = 'Thinking…';
    try {
      /** @type {Hint} */
      const plan = await request('POST', `/api/rooms/${encodeURIComponent(this.roomId)}/hint`,
        { token });
      this.plan = plan;
      this.caption.textContent = describeHint(plan, this.maxSpeed());
      this.tryButton.hidden = false;
    } catch (e) {
      this.plan = null;
      this.caption.textContent = e instanceof Error ? e.message : String(e);
    } finally {
      this.asking = false;
      this.button.disabled = false;
    }
  }

  /** Forget the plan (the balls moved). */
  clear() {
    this.plan = null;
    this.tryButton.hidden = true;
    this.caption.hidden = true;
    this.caption.textContent = '';
  }

  /**
   * Draw the plan over the table (`drawPlan`).
   * @param {CanvasRenderingContext2D} ctx
   * @param {import('./geometry.js').View} view
   * @param {import('./geometry.js').Table} table
   * @param {{id: number, x: number, y: number}[]} balls
   * @param {[number, number] | null} cue where the cue ball is now
   * @param {{cue_mass_ratio: number, max_speed: number}} limits
   */
  draw(ctx, view, table, balls, cue, limits) {
    if (this.plan) drawPlan(ctx, view, table, balls, cue, limits, this.plan);
  }
}

/**
 * Draw a planned shot: a ghost cue ball where it would be placed, the aim line to the ghost
 * ball (with the squirt of side spin) and the object ball's path, and the cue drawn back.
 * The replay's analysis draws the pro's best shot with it too.
 * @param {CanvasRenderingContext2D} ctx
 * @param {import('./geometry.js').View} view
 * @param {import('./geometry.js').Table} table
 * @param {{id: number, x: number, y: number}[]} balls
 * @param {[number, number] | null} cue where the cue ball is now
 * @param {{cue_mass_ratio: number, max_speed: number}} limits
 * @param {{place: [number, number] | null, angle: number, speed: number, tip: [number, number]}} plan
 * @param {number} [cueAlpha] how opaque the cue is drawn
 */
export function drawPlan(ctx, view, table, balls, cue, limits, plan, cueAlpha = 0.6) {
  /** @type {[number, number] | null} */
  const from = plan.place ?? cue;
  if (!from) return;
  const others = balls.filter((b) => b.id !== 0);
  if (plan.place) {
    const [x, y] = view.toScreen(from[0], from[1]);
    ctx.save();
    ctx.fillStyle = 'rgba(255,255,255,0.35)';
    ctx.beginPath();
    ctx.arc(x, y, table.ball_radius * view.scale, 0, Math.PI * 2);
    ctx.fill();
    ctx.restore();
  }
  const path = plan.angle + squirt(plan.tip[0], limits.cue_mass_ratio);
  const guide = castGuide(table, others, from, path);
  let objectEnd = null;
  if (guide.kind === 'ball' && guide.objectDir && guide.hitId !== null) {
    const r = table.ball_radius;
    const start = /** @type {[number, number]} */ ([guide.contact[0] + guide.objectDir[0] * 2 * r,
      guide.contact[1] + guide.objectDir[1] * 2 * r]);
    objectEnd = objectPath(table, others, start, guide.objectDir, [0, guide.hitId]).end;
  }
  drawGuide(ctx, view, table, from, guide, objectEnd);
  drawCue(ctx, view, table, from, plan.angle, powerFromSpeed(plan.speed, limits.max_speed), cueAlpha);
}
