/**
 * What the live table draws over the cloth besides the balls: the ball-in-hand area under
 * them; over them the shooter's guide and cue (or the relayed aim of the player at the
 * table), the pocket called for the 8 and the shot clock's ring. Drawing only: the caller
 * says what is to be drawn.
 */

import {
  castGuide, squirt, objectPath, placementArea, speedFromPower,
} from '../../geometry.js';
import { curvedGuide } from '../../swerve.js';
import { GUIDE_POWER, MIN_POWER } from '../../input.js';
import {
  drawGuide, drawPath, drawCue, drawPlacement, drawPocketCall, drawPowerMeter, drawClockRing,
} from '../../render.js';
import { URGENT_AT } from '../../ui.js';

/** @typedef {import('../../tableview.js').Frame} Frame */
/** @typedef {{id: number, x: number, y: number}[]} BallList */
/** @typedef {{kind: string, end: [number, number]}} ObjectGuide the object ball's path */

/**
 * The area the cue ball may be put in (ball in hand), with the ball being dragged.
 * @param {Frame} frame
 * @param {any} table
 * @param {string | null} ballInHand
 * @param {{x: number, y: number, free: boolean} | null} dragged
 */
export function drawHandArea({ ctx, view }, table, ballInHand, dragged) {
  const area = placementArea(table, ballInHand);
  if (area) drawPlacement(ctx, view, area, dragged ? { ...dragged, r: table.ball_radius } : null);
}

/**
 * The guide from `cue` along `guide`, ended where the object ball goes.
 * @param {Frame} frame
 * @param {any} table
 * @param {BallList} balls
 * @param {[number, number]} cue
 * @param {import('../../geometry.js').Guide} guide
 * @returns {ObjectGuide | null} the object ball's path when the guide hits one
 */
function drawGuideLine({ ctx, view }, table, balls, cue, guide) {
  const path = objectGuide(table, balls, guide);
  drawGuide(ctx, view, table, cue, guide, path?.end ?? null);
  return path;
}

/**
 * A guide that may bend (a raised cue's swerve): the curve up to its last straight run,
 * then that run as any guide.
 * @param {Frame} frame
 * @param {any} table
 * @param {BallList} balls
 * @param {import('../../swerve.js').CurvedGuide} curved
 * @returns {ObjectGuide | null}
 */
function drawCurvedGuide(frame, table, balls, { bends, from, guide }) {
  if (bends.length) drawPath(frame.ctx, frame.view, table, [...bends, from]);
  return drawGuideLine(frame, table, balls, from, guide);
}

/**
 * Where the object ball's guide line ends: the rail, a ball or the pocket it drops in.
 * @param {any} table
 * @param {BallList} balls
 * @param {import('../../geometry.js').Guide} guide
 * @returns {ObjectGuide | null}
 */
function objectGuide(table, balls, guide) {
  if (guide.kind !== 'ball' || !guide.objectDir || guide.hitId === null) return null;
  const hit = balls.find((b) => b.id === guide.hitId);
  if (!hit) return null;
  const path = objectPath(table, balls, [hit.x, hit.y], guide.objectDir, [0, hit.id]);
  return { kind: path.kind, end: path.end };
}

/**
 * The shooter's own aim: guide, cue, and the power meter while pulling back.
 * @param {Frame} frame
 * @param {any} table
 * @param {BallList} balls
 * @param {[number, number]} cue
 * @param {import('../../input.js').AimController} aim
 * @param {import('../../limits.js').Limits} limits the server's limits
 * @returns {ObjectGuide | null}
 */
export function drawOwnAim(frame, table, balls, cue, aim, limits) {
  const path = drawCurvedGuide(frame, table, balls, aim.guide(table, balls, cue, limits));
  drawCue(frame.ctx, frame.view, table, cue, aim.angle, aim.power);
  if (aim.mode === 'pulling') drawPowerMeter(frame.ctx, frame.view, cue, aim.power);
  return path;
}

/**
 * Another player's aim, as relayed: their guide (squirted by their side spin, curved by a
 * raised cue as their own is), their cue a little faded, their power.
 * @param {Frame} frame
 * @param {any} table
 * @param {BallList} balls
 * @param {[number, number]} cue
 * @param {{angle: number, power: number, tip: number[], elevation?: number}} remote
 * @param {import('../../limits.js').Limits} limits
 * @returns {ObjectGuide | null}
 */
export function drawRemoteAim(frame, table, balls, cue, remote, limits) {
  const massRatio = limits.cue_mass_ratio;
  const elevation = remote.elevation ?? 0;
  let path;
  if (elevation > 0) {
    const power = remote.power >= MIN_POWER ? remote.power : GUIDE_POWER;
    const stroke = { angle: remote.angle, speed: speedFromPower(power, limits.max_speed),
      tip: remote.tip, elevation };
    path = drawCurvedGuide(frame, table, balls, curvedGuide(table, balls, cue, stroke, massRatio));
  } else {
    const line = remote.angle + squirt(remote.tip[0] ?? 0, massRatio);
    path = drawGuideLine(frame, table, balls, cue, castGuide(table, balls, cue, line));
  }
  drawCue(frame.ctx, frame.view, table, cue, remote.angle, remote.power, 0.85);
  if (remote.power > 0) drawPowerMeter(frame.ctx, frame.view, cue, remote.power);
  return path;
}

/**
 * The pocket called for the 8: pulsing while the shooter must choose (with the one under
 * the pointer), still once called.
 * @param {Frame} frame
 * @param {any} table
 * @param {{choosing: boolean, called: number | null, hover: number}} call
 * @param {number} now
 */
export function drawCall({ ctx, view }, table, { choosing, called, hover }, now) {
  if (choosing) {
    drawPocketCall(ctx, view, table, called ?? -1, hover, 0.5 + 0.5 * Math.sin(now * 4));
  } else if (called != null) {
    drawPocketCall(ctx, view, table, called, -1, 0);
  }
}

/**
 * The shot clock's ring round the cue ball in its last seconds.
 * @param {Frame} frame
 * @param {any} table
 * @param {[number, number]} cue
 * @param {number | null} left seconds on the clock
 * @param {number} now
 */
export function drawClock({ ctx, view }, table, cue, left, now) {
  if (left === null || left > URGENT_AT) return;
  drawClockRing(ctx, view, table, cue, left / URGENT_AT, 0.5 + 0.5 * Math.sin(now * 10));
}
