/**
 * A finished match's analysis on its replay page (`GET /api/matches/{id}/analysis`,
 * docs/protocol.md): asked for with "Analyse" (or at once with `?analyse=1`, the way the
 * table page's "Analyse" opens it), polled while the server says it is pending, then shown
 * as a strip of the match's shots coloured by verdict (a click shows that shot), each
 * player's accuracy, and for the shot on the table what was played against the pro's best
 * choice, which the replay draws over the table (`drawPlan`). A mistake or a blunder can
 * be played again on a practice table set up from its stored table ("Play this position
 * again", `POST /api/drills`).
 */

import { describeHint } from './hint.js';
import { request } from './net.js';
import { DEFAULT_LIMITS } from './limits.js';

const POLL_MS = 2000; // between asks while the analysis is pending
/** @type {Record<string, string>} */
export const VERDICT_WORDS = { best: 'Best', good: 'Good', mistake: 'Mistake', blunder: 'Blunder' };

/**
 * @typedef {{kind: string, target: number | null, pocket: number | null, via: string | null,
 *   call: number | null, angle: number, speed: number, tip: [number, number],
 *   place: [number, number] | null, chance: number, value: number}} BestShot
 * @typedef {{n: number, game: number, seat: number, verdict: string, loss: number,
 *   played_chance: number, played_value: number, ball_in_hand: string | null,
 *   push_out: boolean, best: BestShot}} JudgedShot
 * @typedef {{seat: number, name: string, accuracy: number | null, best: number, good: number,
 *   mistakes: number, blunders: number}} PlayerLine
 * @typedef {{status: 'ready', shots: JudgedShot[], players: PlayerLine[],
 *   turning_points: number[]}} Analysis
 */

/**
 * What the shot judged `shot` was, in one line.
 * @param {JudgedShot} shot
 */
export function judgedWords(shot) {
  const verdict = VERDICT_WORDS[shot.verdict] ?? shot.verdict;
  const played = `Played: ${Math.round(shot.played_chance * 100)} % to pot`;
  const best = describeHint({ level: 'pro', ...shot.best }, DEFAULT_LIMITS.max_speed);
  const lost = shot.loss > 0 ? ` (${Math.round(shot.loss * 100)} points of winning chance lost)` : '';
  return `${verdict}${lost}. ${played}. The pro: ${best}`;
}

/** @param {number} ms */
const pause = (ms) => new Promise((resolve) => { setTimeout(resolve, ms); });

export class ReplayAnalysis {
  /**
   * @param {string} matchId
   * @param {(n: number) => void} onPick show the match's shot numbered `n`
   */
  constructor(matchId, onPick) {
    this.matchId = matchId;
    this.onPick = onPick;
    /** @type {Analysis | null} */
    this.data = null;
    /** @type {Map<number, JudgedShot>} by the shot's `n` */
    this.byN = new Map();
    this.asking = false;
    this.n = 0; // the shot on the table
    this.button = /** @type {HTMLButtonElement} */ (document.getElementById('replay-analyse'));
    this.status = /** @type {HTMLElement} */ (document.getElementById('analysis-status'));
    this.strip = /** @type {HTMLElement} */ (document.getElementById('analysis-strip'));
    this.accuracy = /** @type {HTMLElement} */ (document.getElementById('analysis-accuracy'));
    this.caption = /** @type {HTMLElement} */ (document.getElementById('analysis-shot'));
    this.drill = /** @type {HTMLButtonElement} */ (document.getElementById('analysis-drill'));
    this.button.addEventListener('click', () => { this.start(); });
    this.drill.addEventListener('click', () => { this.playAgain(); });
  }

  /** Open a practice table on the shot on the table's position, and go there. */
  async playAgain() {
    this.drill.disabled = true;
    try {
      const created = await request('POST', '/api/drills',
        { match_id: Number(this.matchId), n: this.n });
      location.assign(created.url);
    } catch (e) {
      this.status.textContent = e instanceof Error ? e.message : String(e);
      this.drill.disabled = false;
    }
  }

  /** Ask for the analysis until it is ready (or refused). */
  async start() {
    if (this.asking || this.data) return;
    this.asking = true;
    this.button.disabled = true;
    this.status.textContent = 'Analysing…';
    try {
      for (;;) {
        const res = await fetch(`/api/matches/${encodeURIComponent(this.matchId)}/analysis`);
        const body = await res.json().catch(() => null);
        const storing = res.status === 409 && body?.detail?.code === 'match_playing';
        if (res.status === 202 || storing) {
          // (409: the match just ended and is being stored: ask again in a moment)
          const ahead = body?.position ? ` (${body.position} ahead of this match)` : '';
          this.status.textContent = `Analysing…${ahead}`;
          await pause(POLL_MS);
          continue;
        }
        if (!res.ok) throw new Error(body?.detail?.message ?? `the server answered ${res.status}`);
        this.show(/** @type {Analysis} */ (body));
        return;
      }
    } catch (e) {
      this.status.textContent = `No analysis: ${e instanceof Error ? e.message : String(e)}`;
      this.button.disabled = false;
    } finally {
      this.asking = false;
    }
  }

  /** @param {Analysis} data */
  show(data) {
    this.data = data;
    this.byN = new Map(data.shots.map((s) => [s.n, s]));
    this.button.hidden = true;
    this.status.textContent = data.turning_points.length
      ? `Turning points: shot ${data.turning_points.join(', ')}.` : 'No turning point.';
    this.accuracy.replaceChildren(...data.players.map((p) => {
      const line = document.createElement('div');
      line.dataset.testid = 'accuracy';
      const acc = p.accuracy === null ? '–' : `${p.accuracy.toFixed(1)}`;
      line.textContent = `${p.name}: accuracy ${acc} · ${p.mistakes} mistakes, ${p.blunders} blunders`;
      return line;
    }));
    this.strip.replaceChildren(...data.shots.map((s) => {
      const cell = document.createElement('button');
      cell.className = `verdict verdict-${s.verdict}`;
      cell.dataset.testid = 'verdict';
      cell.dataset.verdict = s.verdict;
      cell.dataset.n = String(s.n);
      cell.title = `Shot ${s.n}: ${VERDICT_WORDS[s.verdict] ?? s.verdict}`;
      cell.setAttribute('aria-label', cell.title);
      cell.addEventListener('click', () => this.onPick(s.n));
      return cell;
    }));
    this.select(this.n);
  }

  /**
   * The shot numbered `n` is on the table: mark it in the strip, say how it was judged.
   * @param {number} n
   */
  select(n) {
    this.n = n;
    if (!this.data) return;
    for (const cell of /** @type {HTMLElement[]} */ ([...this.strip.children])) {
      cell.classList.toggle('current', cell.dataset.n === String(n));
    }
    const shot = this.byN.get(n);
    this.caption.textContent = shot ? judgedWords(shot) : '';
    this.caption.dataset.verdict = shot?.verdict ?? '';
    this.drill.hidden = !(shot && (shot.verdict === 'mistake' || shot.verdict === 'blunder'));
  }

  /** The pro's best choice for the shot on the table, once analysed. */
  best() {
    return this.byN.get(this.n)?.best ?? null;
  }

  /** The judged shot on the table, once analysed. */
  current() {
    return this.byN.get(this.n) ?? null;
  }
}
