/**
 * `/login`: signing in to an account kept on another device, with a passkey (a
 * discoverable credential: no name to type) or a name and password. After signing in on a
 * device where another guest played, the player is asked whether that guest's unranked
 * matches join the account (ratings never do); then the profile is shown.
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

export function startLogin() {
  const root = /** @type {HTMLElement} */ (document.getElementById('login'));
  root.hidden = false;
  document.title = 'Pool online · sign in';
  const error = el('p', { class: 'error', role: 'alert', 'data-testid': 'login-error' });
  const panel = el('section', { class: 'panel' });
  panel.append(el('h1', {}, 'Sign in'), el('p', { class: 'muted small' },
    'Your player, its name, ratings and matches, on this device too. No account? Just play: '
    + 'keep your player from its profile when you want to.'));
  const passkey = el('button', { class: 'primary', 'data-testid': 'login-passkey' },
    'Sign in with a passkey');
  passkey.addEventListener('click', () => signIn(() => accounts.passkeySignIn(), error));
  if (!passkeysSupported()) passkey.setAttribute('disabled', '');
  const top = el('div', { class: 'row' });
  top.append(passkey);
  panel.append(top, el('p', { class: 'muted small' }, 'or with your name and password:'),
    passwordForm(error), error);
  const nav = el('p', { class: 'small' });
  nav.append(el('a', { href: '/' }, '← Lobby'));
  root.replaceChildren(nav, panel);
}

/** @param {HTMLElement} error */
function passwordForm(error) {
  const form = el('form', { class: 'row', 'data-testid': 'login-form' });
  const name = /** @type {HTMLInputElement} */ (el('input', {
    'data-testid': 'login-name', autocomplete: 'username', required: '' }));
  const password = /** @type {HTMLInputElement} */ (el('input', {
    type: 'password', 'data-testid': 'login-password', autocomplete: 'current-password',
    required: '' }));
  const nameField = el('label', { class: 'field' }, 'Name');
  nameField.append(name);
  const passwordField = el('label', { class: 'field' }, 'Password');
  passwordField.append(password);
  form.append(nameField, passwordField,
    el('button', { type: 'submit', 'data-testid': 'login-submit' }, 'Sign in'));
  form.addEventListener('submit', (event) => {
    event.preventDefault();
    signIn(() => accounts.login(name.value, password.value), error);
  });
  return form;
}

/**
 * @param {() => Promise<unknown>} how
 * @param {HTMLElement} error
 */
async function signIn(how, error) {
  error.textContent = '';
  try {
    await how();
  } catch (e) {
    const code = /** @type {any} */ (e)?.code;
    error.textContent = code === 'bad_credentials' ? 'Wrong name or password.'
      : code === 'rate_limited' ? 'Too many attempts: wait a few minutes, then try again.'
        : messageOf(e);
    return;
  }
  const { guest } = await accounts.mergeOffer().catch(() => ({ guest: null }));
  if (guest) askMerge(guest, error);
  else location.assign('/profile');
}

/**
 * The merge question: this device's other guest and its unranked matches.
 * @param {{name: string, matches: number}} guest
 * @param {HTMLElement} error
 */
function askMerge(guest, error) {
  const root = /** @type {HTMLElement} */ (document.getElementById('login'));
  const panel = el('section', { class: 'panel', 'data-testid': 'merge-question' });
  const count = guest.matches === 1 ? 'a match' : `${guest.matches} matches`;
  panel.append(el('h2', {}, 'Bring your matches along?'), el('p', {},
    `On this device you also played as "${guest.name}" (${count}, not ranked). Add them to `
    + 'your account\'s matches? Ratings stay as they are.'));
  const yes = el('button', { class: 'primary', 'data-testid': 'merge-yes' }, 'Add them');
  const no = el('button', { 'data-testid': 'merge-no' }, 'Leave them');
  const answer = (/** @type {boolean} */ merge) => accounts.answerMerge(merge)
    .then(() => location.assign('/profile'), (e) => { error.textContent = messageOf(e); });
  yes.addEventListener('click', () => answer(true));
  no.addEventListener('click', () => answer(false));
  const row = el('div', { class: 'row' });
  row.append(yes, no);
  panel.append(row, error);
  root.replaceChildren(panel);
}
