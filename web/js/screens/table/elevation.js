/**
 * The elevation control: a side view of the cue over the cue ball, showing the cue's angle
 * above the bed and where its tip meets the ball, beside the spin widget. The player drags
 * the cue (mouse, pen or touch) or, with the view focused, presses the arrow keys (Shift:
 * ten degrees a press; Home / End: level / steepest). The range input behind it is the
 * accessible control and the one value: the view only moves it.
 */

import { $, $input, setText } from '../../ui.js';

const SVG = 'http://www.w3.org/2000/svg';
// The drawing, in the view's own units (its viewBox is 0 0 WIDTH HEIGHT).
const WIDTH = 96;
const HEIGHT = 72;
const BED = 64; // the bed's line
const BALL = 14; // the ball's radius
const CENTRE = [68, BED - BALL];
const CUE_LENGTH = 90;
const GAP = 3; // between the tip and the ball, so both are seen
const STEP = 1; // degrees per arrow press (x10 with Shift)

/**
 * @typedef {object} ElevationControl
 * @property {(degrees: number) => void} set move the control (a tried hint, a new shot)
 * @property {(tipHeight: number, remote: number | null) => void} show draw the cue at the
 *   control's angle (or at `remote` degrees, another player's cue) with the tip
 *   `tipHeight` of the radius above the centre, seen along the cue
 */

/**
 * Bind the side view `#elevation-view` and the range input `#elevation`.
 * @param {(radians: number) => void} onPick the elevation the player chose
 * @returns {ElevationControl}
 */
export function elevationControl(onPick) {
  const input = $input('elevation');
  const out = $('elevation-out');
  const view = /** @type {SVGSVGElement} */ (/** @type {unknown} */ ($('elevation-view')));
  const cue = sideView(view);
  const max = () => Number(input.max);
  /** @param {number} degrees */
  const set = (degrees) => {
    input.value = String(Math.round(Math.min(Math.max(degrees, 0), max())));
    changed();
  };
  const changed = () => {
    setText(out, `${input.value}°`);
    view.setAttribute('aria-valuenow', input.value);
    view.setAttribute('aria-valuetext', `${input.value} degrees`);
    onPick((Number(input.value) * Math.PI) / 180);
  };
  input.addEventListener('input', changed);
  bindDrag(view, set);
  view.addEventListener('keydown', (ev) => {
    const now = Number(input.value);
    const step = STEP * (ev.shiftKey ? 10 : 1);
    /** @type {Record<string, number>} */
    const to = { ArrowUp: now + step, ArrowRight: now + step, ArrowDown: now - step,
      ArrowLeft: now - step, PageUp: now + 10, PageDown: now - 10, Home: 0, End: max() };
    if (!(ev.key in to)) return;
    ev.preventDefault();
    ev.stopPropagation(); // the table's arrow keys turn the aim: not while here
    set(to[ev.key]);
  });
  return {
    set,
    show: (tipHeight, remote) => {
      cue.draw(remote ?? Number(input.value), tipHeight);
      view.classList.toggle('remote', remote !== null);
    },
  };
}

/**
 * Dragging on the view points the cue at the ball from where the pointer is.
 * @param {SVGSVGElement} view
 * @param {(degrees: number) => void} set
 */
function bindDrag(view, set) {
  /** @param {PointerEvent} ev */
  const pick = (ev) => {
    const r = view.getBoundingClientRect();
    const x = ((ev.clientX - r.left) / r.width) * WIDTH;
    const y = ((ev.clientY - r.top) / r.height) * HEIGHT;
    set((Math.atan2(CENTRE[1] - y, CENTRE[0] - x) * 180) / Math.PI);
  };
  view.addEventListener('pointerdown', (ev) => {
    view.setPointerCapture(ev.pointerId);
    view.focus();
    pick(ev);
    ev.preventDefault();
  });
  view.addEventListener('pointermove', (ev) => { if (ev.buttons) pick(ev); });
}

/**
 * The drawing: the bed, the ball and the cue, redrawn only when the angle or tip changes.
 * @param {SVGSVGElement} view
 */
function sideView(view) {
  view.setAttribute('viewBox', `0 0 ${WIDTH} ${HEIGHT}`);
  const make = (/** @type {string} */ tag, /** @type {Record<string, string | number>} */ at) => {
    const el = document.createElementNS(SVG, tag);
    for (const [k, v] of Object.entries(at)) el.setAttribute(k, String(v));
    view.appendChild(el);
    return el;
  };
  make('line', { x1: 0, y1: BED, x2: WIDTH, y2: BED, class: 'elevation-bed' });
  make('circle', { cx: CENTRE[0], cy: CENTRE[1], r: BALL, class: 'elevation-ball' });
  const line = make('line', { class: 'elevation-cue' });
  const tip = make('circle', { r: 2.2, class: 'elevation-tip' });
  let key = '';
  return {
    /**
     * @param {number} degrees
     * @param {number} tipHeight fraction of the radius, seen along the cue
     */
    draw(degrees, tipHeight) {
      const next = `${degrees}:${tipHeight.toFixed(2)}`;
      if (next === key) return;
      key = next;
      const [contact, butt] = cueLine(degrees, tipHeight);
      line.setAttribute('x1', contact[0].toFixed(1));
      line.setAttribute('y1', contact[1].toFixed(1));
      line.setAttribute('x2', butt[0].toFixed(1));
      line.setAttribute('y2', butt[1].toFixed(1));
      tip.setAttribute('cx', contact[0].toFixed(1));
      tip.setAttribute('cy', contact[1].toFixed(1));
      view.dataset.degrees = String(degrees);
    },
  };
}

/**
 * Where the cue's tip and butt are drawn: the cue's axis passes `tipHeight` radii above the
 * centre (square to the cue) and stops a little short of the ball's surface.
 * @param {number} degrees
 * @param {number} tipHeight
 * @returns {[[number, number], [number, number]]}
 */
export function cueLine(degrees, tipHeight) {
  const t = (degrees * Math.PI) / 180;
  const d = [Math.cos(t), Math.sin(t)]; // from the butt towards the ball (screen y down)
  const up = [d[1], -d[0]]; // square to the cue, away from the bed
  const h = Math.max(-0.95, Math.min(0.95, tipHeight));
  const depth = BALL * Math.sqrt(1 - h * h) + GAP;
  const contact = [CENTRE[0] + up[0] * h * BALL - d[0] * depth,
    CENTRE[1] + up[1] * h * BALL - d[1] * depth];
  return [[contact[0], contact[1]],
    [contact[0] - d[0] * CUE_LENGTH, contact[1] - d[1] * CUE_LENGTH]];
}
