/**
 * The web client's playback, fed the server's real `motion` messages (bench/fidelity.py).
 *
 * Reads JSON from stdin: {cases: [{motion: base64 of the binary message, times: [s...]}]};
 * each message goes the way a browser's does (decoded as net.js decodes a binary message,
 * reduced by state.js, carried out by playback.js's ShotPlayback), then
 * `ShotPlayback.track(t)`, what `window.pool.track(t)` returns, is asked at each time.
 * Writes {cases: [[[id, x, y, cel], ...] per time]} to stdout.
 */

import { readFileSync } from 'node:fs';
import { decodeMotion, base64Bytes } from '../web/js/track.js';
import { initialState, reduce } from '../web/js/state.js';
import { ShotPlayback } from '../web/js/playback.js';

const input = JSON.parse(readFileSync(0, 'utf8'));
const out = [];
for (const c of input.cases) {
  let state = initialState();
  const playback = new ShotPlayback();
  const message = decodeMotion(base64Bytes(c.motion)); // as net.js decodes a binary frame
  const r = reduce(state, message, 0);
  state = r.state;
  for (const e of r.effects) playback.apply(e, 0);
  out.push(c.times.map((/** @type {number} */ t) => playback.track(t)
    .map((b) => [b.id, b.x, b.y, b.cel])));
}
process.stdout.write(JSON.stringify({ cases: out }));
