/**
 * The first-shot hint: an overlay over the table that shows a newcomer the gesture (press
 * on the ball you aim at, pull back, let go), shown on their turn until they have shot once
 * or closed it, and remembered in localStorage so it never comes back.
 */

const KEY = 'pool.firstShotHint';

export class Coach {
  /**
   * @param {HTMLElement} el the overlay
   * @param {HTMLElement} ok its "Got it" button
   * @param {Storage | undefined} [store]
   */
  constructor(el, ok, store = globalThis.localStorage) {
    this.el = el;
    this.store = store;
    ok.addEventListener('click', () => this.done());
  }

  /** True once the hint was followed or closed (on this browser). */
  get seen() {
    try { return this.store?.getItem(KEY) === 'done'; } catch { return false; }
  }

  /** The newcomer shot (or closed the hint): never show it again. */
  done() {
    try { this.store?.setItem(KEY, 'done'); } catch { /* private mode: this page only */ }
    this.el.hidden = true;
  }

  /**
   * Show the hint when it is wanted now (the player's turn to shoot) and not yet seen.
   * @param {boolean} wanted
   */
  show(wanted) {
    const hidden = !(wanted && !this.seen);
    if (this.el.hidden !== hidden) this.el.hidden = hidden;
  }
}
