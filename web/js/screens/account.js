/**
 * The account part of your own profile. A guest sees "Keep this player": add a passkey or
 * set a password, and the player (name, ratings, matches) signs in on any device. An
 * account sees its passkeys and signed-in sessions, each removable, the password form
 * (the old one needed to change it), sign out and sign out everywhere.
 */

import { accounts, passkeysSupported } from '../accounts.js';

/**
 * @param {string} tag
 * @param {Record<string, string>} [attrs]
 * @param {string} [text]
 */
function el(tag, attrs = {}, text = '') {
  const node = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) node.setAttribute(k, v);
  if (text) node.textContent = text;
  return node;
}

/** @param {unknown} e */
const messageOf = (e) => (e instanceof Error ? e.message : String(e));
/** @param {number} t seconds */
const when = (t) => new Date(t * 1000).toLocaleString();

/**
 * @param {any} profile the asking player's own
 * @returns {HTMLElement}
 */
export function accountPanel(profile) {
  const panel = el('section', { class: 'panel', 'data-testid': 'account-panel' });
  const error = el('p', { class: 'error', role: 'alert', 'data-testid': 'account-error' });
  const reload = () => location.reload();
  /** @param {() => Promise<unknown>} fn */
  const act = (fn) => fn().then(reload, (e) => { error.textContent = messageOf(e); });
  const addPasskey = el('button', { class: 'primary', 'data-testid': 'add-passkey' },
    'Add a passkey');
  addPasskey.addEventListener('click', () => act(() => accounts.addPasskey()));
  if (!passkeysSupported()) addPasskey.setAttribute('disabled', '');
  if (!profile.account) {
    panel.append(el('h2', {}, 'Keep this player'), el('p', { class: 'muted small' },
      'Right now this player lives in this browser only. Add a passkey (this device, a phone '
      + 'or a security key) or a password to sign in anywhere with the same name, ratings '
      + 'and matches.'));
    const row = el('div', { class: 'row' });
    row.append(addPasskey);
    panel.append(row, passwordForm(false, act), error);
    return panel;
  }
  panel.append(el('h2', {}, 'Account'), el('p', { class: 'muted small' },
    'Signed in: this player is kept on every device you sign in on.'));
  const passkeys = el('ul', { class: 'rooms', 'data-testid': 'passkey-list' });
  const sessions = el('ul', { class: 'rooms', 'data-testid': 'session-list' });
  const out = el('button', { 'data-testid': 'sign-out' }, 'Sign out');
  out.addEventListener('click', () => act(() => accounts.logout()));
  const everywhere = el('button', { 'data-testid': 'sign-out-everywhere' },
    'Sign out everywhere');
  everywhere.addEventListener('click', () => act(() => accounts.logoutEverywhere()));
  const actions = el('div', { class: 'row' });
  actions.append(addPasskey, out, everywhere);
  const password = el('div', { 'data-testid': 'password-part' });
  panel.append(el('h3', {}, 'Passkeys'), passkeys, el('h3', {}, 'Signed in on'), sessions,
    el('h3', {}, 'Password'), password, actions, error);
  fillLists(passkeys, sessions, act, error);
  accounts.state().then((s) => password.append(passwordForm(s.password, act)),
    (e) => { error.textContent = messageOf(e); });
  return panel;
}

/**
 * @param {boolean} change a password is set (the old one is asked), or none yet
 * @param {(fn: () => Promise<unknown>) => void} act
 */
function passwordForm(change, act) {
  const form = el('form', { class: 'row', 'data-testid': 'password-form' });
  /** @param {string} label @param {string} testid @param {string} complete */
  const field = (label, testid, complete) => {
    const input = /** @type {HTMLInputElement} */ (el('input',
      { type: 'password', 'data-testid': testid, autocomplete: complete, required: '' }));
    const wrap = el('label', { class: 'field' }, label);
    wrap.append(input);
    form.append(wrap);
    return input;
  };
  const old = change ? field('Current password', 'old-password', 'current-password') : null;
  const password = field(change ? 'New password' : 'Password (8 characters or more)',
    'new-password', 'new-password');
  form.append(el('button', { type: 'submit', 'data-testid': 'set-password' },
    change ? 'Change password' : 'Set password'));
  form.addEventListener('submit', (event) => {
    event.preventDefault();
    act(() => accounts.setPassword(password.value, old?.value));
  });
  return form;
}

/**
 * @param {HTMLElement} passkeys
 * @param {HTMLElement} sessions
 * @param {(fn: () => Promise<unknown>) => void} act
 * @param {HTMLElement} error
 */
async function fillLists(passkeys, sessions, act, error) {
  try {
    const [keys, signed] = await Promise.all([accounts.passkeys(), accounts.sessions()]);
    for (const k of keys.passkeys) {
      passkeys.append(item(`${k.label}`, `added ${when(k.created_at)}`
        + (k.last_used ? `, last used ${when(k.last_used)}` : ''), 'passkey',
      () => act(() => accounts.removePasskey(k.id))));
    }
    if (!keys.passkeys.length) passkeys.append(el('li', { class: 'muted' }, 'No passkey yet.'));
    for (const s of signed.sessions) {
      sessions.append(item(s.current ? `${s.label} (this device)` : s.label,
        `since ${when(s.created_at)}, last seen ${when(s.last_seen)}`, 'session',
        () => act(() => accounts.revokeSession(s.id))));
    }
  } catch (e) { error.textContent = messageOf(e); }
}

/**
 * @param {string} title
 * @param {string} detail
 * @param {string} kind
 * @param {() => void} remove
 */
function item(title, detail, kind, remove) {
  const li = el('li', { 'data-testid': kind });
  const what = el('div', { class: 'what' });
  what.append(el('div', {}, title), el('div', { class: 'who' }, detail));
  const button = el('button', { 'data-testid': `remove-${kind}` },
    kind === 'session' ? 'Sign out' : 'Remove');
  button.addEventListener('click', remove);
  li.append(what, button);
  return li;
}
