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

/** @param {number} id */
export function isStripe(id) {
  return id >= 9 && id <= 15;
}

/** @param {number} id */
export function ballColor(id) {
  return BALL_COLORS[id >= 9 ? id - 8 : id];
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
