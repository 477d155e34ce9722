/**
 * The canvas a table is drawn on, shared by the live table and the replay: the backing
 * store in device pixels, the cloth and rails pre-drawn on a layer of their own, and the
 * ball sprites at the ball's pixel size. Rebuilt only when the size or the table changes.
 */

import { makeView } from './geometry.js';
import { buildSprites, context2d } from './sprites.js';
import { drawTable } from './render.js';
import { ballIds } from './balls.js';

export class TableCanvas {
  /**
   * @param {HTMLCanvasElement} canvas
   * @param {HTMLElement} wrap the element whose size the canvas fills
   */
  constructor(canvas, wrap) {
    this.canvas = canvas;
    this.wrap = wrap;
    this.ctx = context2d(canvas);
    /** @type {import('./geometry.js').View | null} */
    this.view = null;
    this.dpr = 1;
    /** @type {import('./sprites.js').Sprites | null} the ball sprites at the current size */
    this.sprites = null;
    /** @type {HTMLCanvasElement | null} the cloth and rails, drawn once per size */
    this.layer = null;
    this.key = '';
    /** @type {import('./geometry.js').Table | null} */
    this.table = null;
    new ResizeObserver(() => this.invalidate()).observe(wrap);
    matchMedia(`(resolution: ${window.devicePixelRatio}dppx)`)
      .addEventListener?.('change', () => this.invalidate());
  }

  invalidate() { this.key = ''; }

  /**
   * Fit `table` to the wrap; true when there is something to draw on.
   * @param {import('./geometry.js').Table | null | undefined} table
   * @returns {this is {view: import('./geometry.js').View}}
   */
  layout(table) {
    if (!table) return false;
    if (table !== this.table) { this.table = table; this.key = ''; }
    // The wrap's padding (a phone's strip under the table for the aim's words and fine
    // aim: style.css) is kept free of the table.
    const pad = getComputedStyle(this.wrap);
    const w = Math.max(50, this.wrap.clientWidth - parseFloat(pad.paddingLeft || '0')
      - parseFloat(pad.paddingRight || '0'));
    const h = Math.max(50, this.wrap.clientHeight - parseFloat(pad.paddingTop || '0')
      - parseFloat(pad.paddingBottom || '0'));
    this.dpr = window.devicePixelRatio || 1;
    const key = `${w}x${h}@${this.dpr}`;
    if (key !== this.key) {
      this.key = key;
      this.canvas.width = Math.round(w * this.dpr);
      this.canvas.height = Math.round(h * this.dpr);
      this.view = makeView(table, w, h);
      this.layer = document.createElement('canvas');
      this.layer.width = this.canvas.width;
      this.layer.height = this.canvas.height;
      const tctx = context2d(this.layer);
      tctx.setTransform(this.dpr, 0, 0, this.dpr, 0, 0);
      drawTable(tctx, table, this.view);
      const rPx = table.ball_radius * this.view.scale * this.dpr;
      const style = table.style ?? 'pool';
      if (!this.sprites || this.sprites.style !== style
        || Math.abs(this.sprites.radius - rPx) > this.sprites.radius * 0.08) {
        this.sprites = buildSprites(rPx, ballIds(style), style);
      }
    }
    return !!(this.view && this.layer);
  }

  /** Paint the empty table; the context is left in CSS pixels for what comes on top. */
  begin() {
    const { ctx } = this;
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    if (this.layer) ctx.drawImage(this.layer, 0, 0);
    ctx.setTransform(this.dpr, 0, 0, this.dpr, 0, 0);
    return ctx;
  }
}
