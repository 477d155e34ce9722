/** The balls: colours, stripes and groups. Pure data shared by sprites, HUD and tests. */

export const CUE = 0;
export const EIGHT = 8;

/** @type {Record<number, string>} Base colour of each number (9-15 repeat 1-7 as stripes). */
export const BALL_COLORS = {
  0: '#f7f3e6', // cue: ivory white
  1: '#f4c20d', // yellow
  2: '#1b4fb5', // blue
  3: '#d3231d', // red
  4: '#55308d', // purple
  5: '#f26a1b', // orange
  6: '#12814a', // green
  7: '#7d1c22', // maroon
  8: '#151515', // black
};

export const SOLIDS = [1, 2, 3, 4, 5, 6, 7];
export const STRIPES = [9, 10, 11, 12, 13, 14, 15];

/**
 * Snooker's balls (the server's ids): 1-15 the reds, 16-21 yellow to black.
 * @type {Record<number, string>}
 */
export const SNOOKER_COLORS = {
  0: '#f7f3e6',
  16: '#f4d21d', // yellow
  17: '#138a43', // green
  18: '#7a4a1e', // brown
  19: '#1d4fc2', // blue
  20: '#f08cb0', // pink
  21: '#111111', // black
};
const SNOOKER_RED = '#c8141b';

/**
 * Carom's balls (the server's ids): the white and the yellow cue balls, and the red.
 * @type {Record<number, string>}
 */
export const CAROM_COLORS = { 0: '#f7f3e6', 1: '#f4c20d', 2: '#c8141b' };
/** @type {Record<number, string>} */
export const CAROM_NAMES = { 0: 'white', 1: 'yellow', 2: 'red' };

/** @type {Record<number, string>} snooker colours by id, as players name them */
export const SNOOKER_NAMES = {
  16: 'yellow', 17: 'green', 18: 'brown', 19: 'blue', 20: 'pink', 21: 'black',
};

/**
 * @param {number} id
 * @param {string} [style] the table's style: "pool" or "snooker"
 */
export function isStripe(id, style = 'pool') {
  return style === 'pool' && id >= 9 && id <= 15;
}

/**
 * @param {number} id
 * @param {string} [style] the table's style: "pool" or "snooker"
 */
export function ballColor(id, style = 'pool') {
  if (style === 'snooker') return SNOOKER_COLORS[id] ?? SNOOKER_RED;
  if (style === 'carom') return CAROM_COLORS[id] ?? SNOOKER_RED;
  return BALL_COLORS[id >= 9 ? id - 8 : id];
}

/**
 * A practice table's kind (one player, no race): on the pool, snooker or carom table.
 * @param {string | null | undefined} kind
 */
export function isPractice(kind) {
  return kind === 'practice' || kind === 'snooker_practice' || kind === 'three_cushion_practice';
}

/**
 * "the pink", "a red": a snooker ball as players name it.
 * @param {number} id
 */
export function snookerBallName(id) {
  return SNOOKER_NAMES[id] ? `the ${SNOOKER_NAMES[id]}` : 'a red';
}

/**
 * The ball ids a table's sprites are built for.
 * @param {string} [style]
 * @returns {number[]}
 */
export function ballIds(style = 'pool') {
  if (style === 'carom') return [0, 1, 2];
  return [...Array(style === 'snooker' ? 22 : 16).keys()];
}

/**
 * Ball ids of a group name ("solids" | "stripes"), else [].
 * @param {string | null} group
 * @returns {number[]}
 */
export function groupBalls(group) {
  if (group === 'solids') return SOLIDS;
  if (group === 'stripes') return STRIPES;
  return [];
}
