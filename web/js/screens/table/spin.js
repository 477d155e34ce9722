/**
 * The spin widget: where the cue tip strikes, within the server's `max_tip`. The player
 * picks it with a press or a drag (a double click centres it); while another player is at
 * the table it shows their spin (from the relayed `aim`).
 */

import { clampTip } from '../../geometry.js';

const SPIN_REACH = 1.2; // the widget's edge, as a multiple of the largest legal tip

export class SpinWidget {
  /**
   * @param {HTMLElement} el the widget (its `.spin-dot` is the tip)
   * @param {() => number} maxTip the server's `limits.max_tip` now
   * @param {(tip: [number, number]) => void} onPick a tip the player chose
   */
  constructor(el, maxTip, onPick) {
    this.el = el;
    this.dot = /** @type {HTMLElement} */ (el.querySelector('.spin-dot'));
    this.maxTip = maxTip;
    /** @param {PointerEvent} ev */
    const pick = (ev) => {
      const r = el.getBoundingClientRect();
      const side = ((ev.clientX - r.left) / r.width - 0.5) * 2 * this.reach();
      const height = -((ev.clientY - r.top) / r.height - 0.5) * 2 * this.reach();
      onPick(clampTip(side, height, maxTip()));
    };
    el.addEventListener('pointerdown', (ev) => {
      el.setPointerCapture(ev.pointerId);
      pick(ev);
    });
    el.addEventListener('pointermove', (ev) => { if (ev.buttons) pick(ev); });
    el.addEventListener('dblclick', () => onPick([0, 0]));
  }

  reach() {
    return this.maxTip() * SPIN_REACH;
  }

  /**
   * Show `tip`; `remote` when it is another player's.
   * @param {number[]} tip
   * @param {boolean} remote
   */
  show(tip, remote) {
    const key = tip.map((v) => v.toFixed(2)).join(',');
    if (this.el.dataset.tip !== key) {
      this.dot.style.left = `${50 + (tip[0] / this.reach()) * 50}%`;
      this.dot.style.top = `${50 - (tip[1] / this.reach()) * 50}%`;
      this.el.dataset.tip = key;
    }
    this.el.classList.toggle('remote', remote);
  }
}
