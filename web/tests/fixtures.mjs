/** Shared test data: the server's 9 ft table as `Table.to_dict()` gives it. */

// The server's 9 ft table (Table.pool("9ft").to_dict(), rounded where irrelevant).
const a = 0.114 / Math.SQRT2;
const L = 2.54;
const W = 1.27;
const s = 0.127 / 2;
/** @type {import('../js/geometry.js').Table} */
export const TABLE = {
  length: L, width: W, ball_radius: 0.028575, head_string: L / 4,
  head_spot: [L / 4, W / 2], foot_spot: [3 * L / 4, W / 2],
  cushions: [
    { start: [a, 0], end: [L / 2 - s, 0], normal: [0, 1] },
    { start: [L / 2 + s, 0], end: [L - a, 0], normal: [0, 1] },
    { start: [L, a], end: [L, W - a], normal: [-1, 0] },
    { start: [L - a, W], end: [L / 2 + s, W], normal: [0, -1] },
    { start: [L / 2 - s, W], end: [a, W], normal: [0, -1] },
    { start: [0, W - a], end: [0, a], normal: [1, 0] },
  ],
  pockets: [
    { name: 'bottom_left', center: [-0.0212, -0.0212], radius: 0.067 },
    { name: 'bottom_side', center: [L / 2, -0.0381], radius: 0.0635 },
    { name: 'bottom_right', center: [L + 0.0212, -0.0212], radius: 0.067 },
    { name: 'top_right', center: [L + 0.0212, W + 0.0212], radius: 0.067 },
    { name: 'top_side', center: [L / 2, W + 0.0381], radius: 0.0635 },
    { name: 'top_left', center: [-0.0212, W + 0.0212], radius: 0.067 },
  ],
};
