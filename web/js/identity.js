/**
 * One person, one name: the profile's (made on a first visit) is the name used at every
 * table, in Play now, results and history. A name field is only ever prefilled with it;
 * a different name typed there renames the profile first, so it is used everywhere from
 * then on. The field shows its limit while typing and says so when a paste was cut.
 */

import { memory } from './net.js';
import { players } from './players.js';
import { DEFAULT_LIMITS } from './limits.js';
import { nameNote, nameProblem } from './names.js';

/** @type {Promise<any> | null} */
let mine = null;
/** @type {Promise<string> | null} */
let known = null;
/** @type {((name: string) => void)[]} */
const listeners = [];

/**
 * The profile's name (the profile made, with its cookie, on a first visit). Asked once per
 * page: two first requests at once would each make a profile.
 */
export function profileName() {
  known ??= myProfile().then((p) => /** @type {string} */ (p.name));
  return known;
}

/** The asking player's whole profile (`GET /api/players/me`), asked once per page. */
export function myProfile() {
  mine ??= players.me();
  return mine;
}

/**
 * Call `fn` with the name now and after every rename made on this page.
 * @param {(name: string) => void} fn
 */
export function onName(fn) {
  listeners.push(fn);
  profileName().then(fn, () => {});
}

/** @param {HTMLInputElement} input */
const limitOf = (input) => (input.maxLength > 0 ? input.maxLength : DEFAULT_LIMITS.max_name);

const SAVE_AFTER = 700; // ms after the last key before a name typed is saved

/**
 * Prefill `input` with the profile's name (unless something was typed first) and show
 * its limit under it while typing. With `save`, a valid name typed is saved to the
 * profile shortly after the last key (and, if the page is left first, on the next page).
 * @param {HTMLInputElement} input
 * @param {boolean} [save]
 */
export function bindNameField(input, save = false) {
  const note = document.createElement('span');
  note.className = 'name-note small muted';
  note.dataset.testid = `${input.dataset.testid ?? 'name'}-note`;
  note.setAttribute('aria-live', 'polite');
  input.insertAdjacentElement('afterend', note);
  let cutFrom = 0;
  const show = () => { note.textContent = nameNote(input.value, limitOf(input), cutFrom); };
  input.addEventListener('paste', (e) => {
    const pasted = e.clipboardData?.getData('text') ?? '';
    const kept = input.value.length - ((input.selectionEnd ?? 0) - (input.selectionStart ?? 0));
    cutFrom = kept + pasted.length;
  });
  input.addEventListener('input', show);
  // A key typed after a cut paste: the note goes back to the count (Ctrl+V's own keydown
  // comes before its paste event).
  input.addEventListener('keydown', () => { cutFrom = 0; });
  let typed = false;
  input.addEventListener('input', () => { typed = true; input.dataset.typed = '1'; }, { once: true });
  onName((name) => { if (!typed) { input.value = name; show(); } });
  if (save) saveAsTyped(input);
  // A name typed on the last page and not saved yet (the page was left first) is the one
  // to play under: shown here, saved with the next action (or now, where fields save).
  const pending = memory.pendingName();
  if (pending) {
    input.value = pending;
    input.dispatchEvent(new Event('input'));
  }
  show();
}

/**
 * Save a valid name typed in `input` to the profile once the typing stops (kept as the
 * pending name meanwhile, for the next page if this one is left first).
 * @param {HTMLInputElement} input
 */
function saveAsTyped(input) {
  /** @type {ReturnType<typeof setTimeout> | undefined} */
  let timer;
  const saveNow = () => settleName(input).catch(() => {});
  input.addEventListener('input', () => {
    clearTimeout(timer);
    const valid = !nameProblem(input.value, limitOf(input));
    memory.setPendingName(valid ? input.value.trim() : '');
    if (valid) timer = setTimeout(saveNow, SAVE_AFTER);
  });
}

/**
 * The name to play under: the field's, checked here first (one sentence when refused),
 * and saved to the profile when it differs from it.
 * @param {HTMLInputElement} input
 * @returns {Promise<string>}
 */
export async function settleName(input) {
  // Pressed before the profile's name came (nothing typed): that name, once it comes.
  if (!input.value.trim() && !input.dataset.typed) {
    try {
      const current = await profileName();
      if (!input.value.trim()) input.value = current;
    } catch { /* no profile: the field's own words below */ }
  }
  const problem = nameProblem(input.value, limitOf(input));
  if (problem) throw new Error(problem);
  const name = input.value.trim();
  let current = '';
  try { current = await profileName(); } catch { /* no profile: the table's name only */ }
  if (current && name !== current) {
    const renamed = await players.rename(name);
    known = Promise.resolve(renamed.name);
    for (const fn of listeners) fn(renamed.name);
  }
  memory.setName(name);
  memory.setPendingName('');
  return name;
}
