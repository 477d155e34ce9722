import { test } from 'node:test';
import assert from 'node:assert/strict';
import { CELS, bodyPoint, surfaceAt, hexToRgb } from '../js/sprites.js';
import { ballColor, isStripe } from '../js/balls.js';

const GRID = 41; // samples across the ball seen from above

/**
 * What a player sees of ball `id` at cel `k` from above: the share of the disc painted in
 * the ball's colour, on a number disc, and in the cue ball's ivory.
 * @param {number} id
 * @param {number} k
 */
function seen(id, k) {
  const theta = (2 * Math.PI * k) / CELS;
  const own = hexToRgb(ballColor(id)).join(',');
  const ivory = hexToRgb(ballColor(0)).join(',');
  let n = 0;
  let colour = 0;
  let number = 0;
  let white = 0;
  for (let i = 0; i < GRID; i++) {
    for (let j = 0; j < GRID; j++) {
      const u = ((i + 0.5) / GRID) * 2 - 1;
      const v = ((j + 0.5) / GRID) * 2 - 1;
      if (u * u + v * v > 0.9) continue; // the limb is dark under the shading anyway
      n += 1;
      const { color, decal } = surfaceAt(id, bodyPoint(u, v, Math.sqrt(1 - u * u - v * v), theta));
      const c = color.join(',');
      if (decal) number += 1;
      else if (c === own) colour += 1;
      if (c === ivory || decal) white += 1;
    }
  }
  return { colour: colour / n, number: number / n, white: white / n };
}

test('every object ball shows its colour and a number from above at every cel', () => {
  for (let id = 1; id <= 15; id++) {
    for (let k = 0; k < CELS; k++) {
      const s = seen(id, k);
      assert.ok(s.colour >= (isStripe(id) ? 0.25 : 0.5),
        `ball ${id} cel ${k}: only ${(100 * s.colour).toFixed(0)} % of its colour shows`);
      assert.ok(s.number >= 0.1,
        `ball ${id} cel ${k}: its number covers ${(100 * s.number).toFixed(0)} %`);
    }
  }
});

test('a striped ball never reads as the cue ball: its band always crosses the top', () => {
  for (let k = 0; k < CELS; k++) {
    const cue = seen(0, k);
    assert.ok(cue.white > 0.9, `the cue ball is white at cel ${k}`);
    for (let id = 9; id <= 15; id++) {
      const s = seen(id, k);
      assert.ok(s.white < 0.7, `ball ${id} cel ${k} is ${(100 * s.white).toFixed(0)} % white`);
      assert.ok(cue.white - s.white > 0.3, `ball ${id} cel ${k} looks like the cue ball`);
    }
  }
});
