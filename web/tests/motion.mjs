/**
 * A `motion` message encoder written from docs/protocol.md alone (the server's is Python),
 * so the tests check the client's decoder against the documented bytes.
 */

/**
 * @typedef {object} TrackSpec
 * @property {number} id
 * @property {number | null} [pocket]
 * @property {number[]} t seconds
 * @property {number[]} x metres
 * @property {number[]} y metres
 * @property {number[]} [phase] radians rolled
 */

/**
 * @param {{seq?: number, shot: number, duration: number, tracks: TrackSpec[],
 *   sounds?: {t: number, kind: string, ids: number[], speed: number, target?: number}[]}} m
 * @returns {Uint8Array}
 */
export function encodeMotion({ seq = 0, shot, duration, tracks, sounds = [] }) {
  /** @type {number[]} */
  const out = [];
  const u8 = (/** @type {number} */ v) => out.push(v & 255);
  const u16 = (/** @type {number} */ v) => { u8(v); u8(v >> 8); };
  const u32 = (/** @type {number} */ v) => { u16(v & 65535); u16(Math.floor(v / 65536)); };
  const varint = (/** @type {number} */ v) => {
    while (v >= 128) { u8((v % 128) | 128); v = Math.floor(v / 128); }
    u8(v);
  };
  const zigzag = (/** @type {number} */ v) => varint(v >= 0 ? 2 * v : -2 * v - 1);
  const kinds = ['strike', 'ball', 'cushion', 'jaw', 'pocket'];
  u8(1); u8(1); u32(seq); u32(shot); u32(Math.round(duration * 1e6)); u8(tracks.length);
  u16(sounds.length);
  for (const tr of tracks) {
    u8(tr.id); u8(tr.pocket ?? 255); u16(tr.t.length);
    const q = tr.t.map((_, k) => [Math.round(tr.t[k] * 1e6), Math.round(tr.x[k] * 1e4),
      Math.round(tr.y[k] * 1e4), Math.round(((tr.phase?.[k] ?? 0) / (2 * Math.PI)) * 4096)]);
    q.forEach(([t, x, y, p], k) => {
      if (k === 0) {
        varint(t); u16(x & 65535); u16(y & 65535); u16(((p % 4096) + 4096) % 4096);
      } else {
        const [pt, px, py, pp] = q[k - 1];
        varint(t - pt); zigzag(x - px); zigzag(y - py); zigzag(p - pp);
      }
    });
  }
  let prev = 0;
  for (const s of sounds) {
    const at = Math.round(s.t * 1e6);
    varint(at - prev);
    prev = at;
    u8(kinds.indexOf(s.kind)); u8(s.ids[0]); u8(s.ids[1] ?? 255);
    u8(s.target === undefined || s.target < 0 ? 255 : s.target); u16(Math.round(s.speed * 1000));
  }
  return Uint8Array.from(out);
}
