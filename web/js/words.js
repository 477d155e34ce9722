/**
 * What the table says to people: outcome texts written once, the rules' decision options
 * as buttons a player understands. Pure (no DOM), tested by `node --test web/tests/`.
 */

/**
 * The sentences of a text, each with its closing punctuation.
 * @param {string} text
 * @returns {string[]}
 */
export function sentences(text) {
  return (text ?? '').split(/(?<=[.!?])\s+/).map((s) => s.trim()).filter(Boolean);
}

/** @param {string} s */
const bare = (s) => s.replace(/[.!?]+$/, '').trim().toLowerCase();

/**
 * An outcome text with every sentence said once: a sentence repeated, or one that a longer
 * sentence of the same text says again with more detail ("Ana pocketed the 8." beside
 * "Ana pocketed the 8 in the called bottom side pocket."), is dropped; the order is kept.
 * @param {string} text
 * @returns {string}
 */
export function tidyOutcome(text) {
  const all = sentences(text);
  const keys = all.map(bare);
  const kept = all.filter((_, i) => {
    const k = keys[i];
    if (!k) return false;
    if (keys.indexOf(k) !== i) return false; // said before
    return !keys.some((other, j) => j !== i && other.length > k.length
      && other.startsWith(k) && /^[\s,;:]/.test(other.slice(k.length)));
  });
  return kept.join(' ');
}

/** @type {Record<string, string>} the rules' decision options, as a player says them */
export const DECISION_LABELS = {
  accept: 'Play from here',
  rerack: 'Re-rack and break',
  rerack_opponent_breaks: 'Re-rack, opponent breaks',
  spot: 'Spot the ball and shoot',
  shoot: 'Take the shot',
  pass: 'Pass it back',
  free_ball: 'Take a free ball',
  play: 'Play from here',
  play_again: 'Make them play again',
  replace: 'Replace the balls, they play again',
};

/**
 * The button text of a decision option (an unknown one reads as words, not as an id).
 * @param {string} option
 */
export function decisionLabel(option) {
  const known = DECISION_LABELS[option];
  if (known) return known;
  const words = option.replace(/_/g, ' ').trim();
  return words.charAt(0).toUpperCase() + words.slice(1);
}

/**
 * "42 s" / "1:05": a countdown shown to people.
 * @param {number} seconds
 */
export function countdown(seconds) {
  const s = Math.max(0, Math.ceil(seconds));
  return s >= 60 ? `${Math.floor(s / 60)}:${String(s % 60).padStart(2, '0')}` : `${s} s`;
}
