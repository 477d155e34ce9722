/**
 * What the server allows (shot speed, tip offset, name and chat lengths) and how it paces
 * its frame stream. The server is the only authority on both: it sends `limits` in the
 * WebSocket `welcome` and from `GET /api/limits`, and the stream's pacing (`tick_hz`,
 * `frame_every`, `frames_per_message`) in `welcome` and in a stored match's `stream`.
 *
 * DEFAULT_LIMITS and DEFAULT_STREAM are the only copies of those numbers in the client.
 * They are used only until the server's message arrives (the lobby before `/api/limits`
 * answers, a table before its `welcome`), or when an older server leaves a field out; every
 * screen replaces them with what the server said as soon as it says it. Pure: no DOM.
 */

/**
 * @typedef {object} Limits
 * @property {number} max_speed cue-ball speed of a shot, m/s
 * @property {number} max_tip tip offset |(side, height)|, fraction of the ball radius
 * @property {number} max_elevation the cue's largest angle above the bed, radians
 * @property {number} max_angle |angle| of a shot or an aim, radians
 * @property {number} max_name characters of a player's name
 * @property {number} max_chat characters of a chat line
 * @property {number} cue_mass_ratio ball mass over the cue's end mass (squirt)
 */

/**
 * @typedef {object} StreamPacing
 * @property {number} tick_hz engine ticks per second (a frame's `tick` / tick_hz = seconds)
 * @property {number} frame_every ticks between two streamed frames
 * @property {number} frames_per_message frames carried by one `frame` message
 */

/** @type {Readonly<Limits>} Stand-in until the server's `limits` arrive (see above). */
export const DEFAULT_LIMITS = Object.freeze({
  max_speed: 12.0,
  max_tip: 0.5,
  max_elevation: 1.3962634015954636,
  max_angle: 10.0,
  max_name: 24,
  max_chat: 200,
  cue_mass_ratio: 30.0,
});

/** @type {Readonly<StreamPacing>} Stand-in until `welcome` or a match's `stream` arrives. */
export const DEFAULT_STREAM = Object.freeze({
  tick_hz: 120,
  frame_every: 6,
  frames_per_message: 4,
});

/** @param {unknown} v */
const positive = (v) => typeof v === 'number' && Number.isFinite(v) && v > 0;

/**
 * Copy the known fields of `source` that are positive numbers over `fallback`; anything
 * missing or malformed keeps the fallback's value, so a partial message cannot leave a
 * limit undefined.
 * @template {object} T
 * @param {unknown} source
 * @param {Readonly<T>} fallback
 * @returns {Readonly<T>}
 */
function pickNumbers(source, fallback) {
  if (!source || typeof source !== 'object') return fallback;
  const src = /** @type {Record<string, unknown>} */ (source);
  /** @type {Record<string, unknown>} */
  const out = { ...fallback };
  let changed = false;
  for (const key of Object.keys(fallback)) {
    const v = src[key];
    if (positive(v) && v !== out[key]) { out[key] = v; changed = true; }
  }
  return changed ? /** @type {Readonly<T>} */ (Object.freeze(out)) : fallback;
}

/**
 * The server's limits (`welcome.limits`, `GET /api/limits`) over `fallback`.
 * @param {unknown} source
 * @param {Readonly<Limits>} [fallback]
 * @returns {Readonly<Limits>}
 */
export function readLimits(source, fallback = DEFAULT_LIMITS) {
  const limits = pickNumbers(source, fallback);
  if (!Number.isInteger(limits.max_name) || !Number.isInteger(limits.max_chat)) {
    return Object.freeze({ ...limits, max_name: Math.floor(limits.max_name),
      max_chat: Math.floor(limits.max_chat) });
  }
  return limits;
}

/**
 * The stream's pacing from `welcome` (top-level fields) or a match's `stream` over
 * `fallback`.
 * @param {unknown} source
 * @param {Readonly<StreamPacing>} [fallback]
 * @returns {Readonly<StreamPacing>}
 */
export function readStream(source, fallback = DEFAULT_STREAM) {
  return pickNumbers(source, fallback);
}
