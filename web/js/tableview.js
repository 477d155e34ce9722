/**
 * The table as both table screens show it: the room state the server's messages are reduced
 * into (state.js), the shot playback they drive (frames, sounds, pocketed balls; playback.js)
 * and the canvas the balls are drawn on (tablecanvas.js). The live table feeds it its room
 * socket's messages; the replay feeds it the streams of the stored shots, so a replay looks
 * and sounds exactly like the game did.
 *
 * Each screen calls `receive` as messages come, `update` once per display frame, and draws
 * with `begin` (the cloth), its own layers, and `drawBalls`.
 */

import { memory } from './net.js';
import { reduce } from './state.js';
import { ShotPlayback } from './playback.js';
import { CELS } from './sprites.js';
import { drawBalls, drawSinking } from './render.js';
import { TableCanvas } from './tablecanvas.js';
import { TableAudio } from './audio.js';

/** @typedef {import('./state.js').RoomState} RoomState */
/** @typedef {import('./state.js').Effect} Effect */
/** @typedef {{ctx: CanvasRenderingContext2D, view: import('./geometry.js').View}} Frame */

export class TableView {
  /**
   * @param {HTMLCanvasElement} canvas
   * @param {HTMLElement} wrap the element whose size the canvas fills
   * @param {RoomState} state the room state to start from
   */
  constructor(canvas, wrap, state) {
    this.canvas = canvas;
    this.surface = new TableCanvas(canvas, wrap);
    this.audio = new TableAudio();
    this.audio.setMuted(memory.muted());
    this.playback = new ShotPlayback({ cels: CELS, delay: 0.1,
      onSound: (sound, speed) => this.audio.play(sound, speed) });
    /** @type {RoomState} */
    this.state = state;
  }

  /**
   * One server message into the state; the effects are returned for the screen, which
   * hands them to `play` once it has done its own part.
   * @param {Record<string, any>} msg
   * @param {number} now local time, seconds
   * @returns {Effect[]}
   */
  receive(msg, now) {
    const res = reduce(this.state, msg, now);
    this.state = res.state;
    return res.effects;
  }

  /**
   * The reducer's effects into the shot playback.
   * @param {Effect[]} effects
   * @param {number} now
   */
  play(effects, now) {
    for (const e of effects) this.playback.apply(e, now);
  }

  /**
   * Move the playback on (frames, due sounds, sinking balls).
   * @param {number} dt
   * @param {number} now
   * @param {number} [pace] playback speed
   */
  update(dt, now, pace = 1) {
    this.playback.update(dt, now, pace);
  }

  /**
   * Paint the empty `table`, laid out to the canvas's size; null when there is nothing to
   * draw on yet (no table).
   * @param {import('./geometry.js').Table | null | undefined} table
   * @returns {Frame | null}
   */
  begin(table) {
    const { surface } = this;
    if (!surface.layout(table)) return null;
    return { ctx: surface.begin(), view: surface.view };
  }

  /**
   * The balls (the playback's, or `balls` where a screen moved one) and the pocketed ones
   * sinking.
   * @param {Frame} frame
   * @param {number} now
   * @param {import('./playback.js').BallMap} [balls]
   */
  drawBalls({ ctx, view }, now, balls = this.playback.balls) {
    const { sprites, dpr } = this.surface;
    if (!sprites) return;
    drawBalls(ctx, view, sprites, balls, 1 / dpr);
    for (const s of this.playback.sinking.list) drawSinking(ctx, view, sprites, s, now, 1 / dpr);
  }

  /** The balls shown now, for the page hooks: [{id, x, y, cel}] in table metres. */
  ballList() {
    return [...this.playback.balls].map(([id, b]) => ({ id, x: b.x, y: b.y, cel: b.cel }));
  }

  /** True once the canvas is laid out and the sprites are built. */
  get ready() {
    return !!(this.surface.view && this.surface.sprites);
  }
}
