/**
 * A player's name as the server takes it (server/players/profile.py `check_name`): stripped,
 * 1 to `max_name` printable characters. Pure, so the sentences are tested without a page:
 * one clear sentence for each refusal, and what the field says while typing.
 */

/**
 * Why a name would be refused, in one sentence; null when it is fine.
 * @param {string} name as typed
 * @param {number} max the server's `max_name`
 * @returns {string | null}
 */
export function nameProblem(name, max) {
  const clean = name.trim();
  if (!clean) return 'Type a name: it cannot be empty.';
  if (clean.length > max) return `That name is too long: at most ${max} characters.`;
  // eslint-disable-next-line no-control-regex
  if (/[\u0000-\u001f\u007f-\u009f]/.test(clean)) {
    return 'A name cannot hold control characters such as tabs or line breaks.';
  }
  return null;
}

/**
 * What the field says under it while typing: how much of the limit is used, and when a
 * paste was cut to fit.
 * @param {string} value the field's value
 * @param {number} max
 * @param {number} [cutFrom] the length a paste would have made, when it was cut
 */
export function nameNote(value, max, cutFrom = 0) {
  const used = `${value.length}/${max} characters`;
  return cutFrom > max ? `${used} · cut to ${max}: the paste had ${cutFrom}.` : used;
}
