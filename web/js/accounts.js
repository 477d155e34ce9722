/**
 * Accounts (docs/protocol.md, "Accounts"): keeping a player across devices with a passkey
 * (WebAuthn, a discoverable credential: signing in needs no name) or a password, signing
 * in and out, the lists of sessions and passkeys, and merging this device's other guest.
 * The session lives in an HttpOnly cookie the page never sees.
 */

import { request } from './net.js';

/** @param {string} text base64url */
function bytesOf(text) {
  const b64 = text.replace(/-/g, '+').replace(/_/g, '/');
  const raw = atob(b64 + '='.repeat((4 - (b64.length % 4)) % 4));
  return Uint8Array.from(raw, (c) => c.charCodeAt(0));
}

/** @param {ArrayBuffer | null} buffer */
function textOf(buffer) {
  if (!buffer) return null;
  let raw = '';
  for (const b of new Uint8Array(buffer)) raw += String.fromCharCode(b);
  return btoa(raw).replace(/\+/g, '-').replace(/\//g, '_').replace(/=+$/, '');
}

/**
 * The server's options (JSON, binary fields base64url) as the browser takes them.
 * @param {any} options
 */
function creationOptions(options) {
  return {
    ...options,
    challenge: bytesOf(options.challenge),
    user: { ...options.user, id: bytesOf(options.user.id) },
    excludeCredentials: (options.excludeCredentials ?? []).map(
      (/** @type {any} */ c) => ({ ...c, id: bytesOf(c.id) })),
  };
}

/** @param {any} options */
function requestOptions(options) {
  return {
    ...options,
    challenge: bytesOf(options.challenge),
    allowCredentials: (options.allowCredentials ?? []).map(
      (/** @type {any} */ c) => ({ ...c, id: bytesOf(c.id) })),
  };
}

/**
 * A credential as JSON for the server (what `toJSON()` gives where it exists).
 * @param {any} credential PublicKeyCredential
 */
function credentialJson(credential) {
  const r = credential.response;
  const response = r.attestationObject
    ? { clientDataJSON: textOf(r.clientDataJSON), attestationObject: textOf(r.attestationObject),
      transports: r.getTransports?.() ?? [] }
    : { clientDataJSON: textOf(r.clientDataJSON), authenticatorData: textOf(r.authenticatorData),
      signature: textOf(r.signature), userHandle: textOf(r.userHandle) };
  return { id: credential.id, rawId: textOf(credential.rawId), type: credential.type, response,
    clientExtensionResults: credential.getClientExtensionResults?.() ?? {} };
}

/** Can this browser use passkeys here (a secure context with WebAuthn)? */
export const passkeysSupported = () =>
  window.isSecureContext && typeof window.PublicKeyCredential === 'function';

export const accounts = {
  /** @param {string} name @param {string} password */
  login: (name, password) => request('POST', '/api/login', { name, password }),
  logout: () => request('POST', '/api/logout'),
  logoutEverywhere: () => request('POST', '/api/logout/everywhere'),
  /** @param {string} password @param {string} [oldPassword] */
  setPassword: (password, oldPassword) => request('POST', '/api/account/password',
    { password, ...(oldPassword ? { old_password: oldPassword } : {}) }),
  /** The signed-in account: `{name, password}` (whether a password is set). */
  state: () => request('GET', '/api/account'),
  sessions: () => request('GET', '/api/account/sessions'),
  /** @param {string} id */
  revokeSession: (id) => request('DELETE', `/api/account/sessions/${encodeURIComponent(id)}`),
  passkeys: () => request('GET', '/api/passkeys'),
  /** @param {string} id */
  removePasskey: (id) => request('DELETE', `/api/passkeys/${encodeURIComponent(id)}`),
  mergeOffer: () => request('GET', '/api/account/merge'),
  /** @param {boolean} merge */
  answerMerge: (merge) => request('POST', '/api/account/merge', { merge }),

  /** Add a passkey to this player (a guest becomes an account, signed in here). */
  async addPasskey() {
    const { options } = await request('POST', '/api/passkeys/register/options');
    const credential = await navigator.credentials.create(
      { publicKey: /** @type {any} */ (creationOptions(options)) });
    return request('POST', '/api/passkeys/register', { credential: credentialJson(credential) });
  },

  /** Sign in with any passkey this device (or a phone nearby) holds for the site. */
  async passkeySignIn() {
    const { options } = await request('POST', '/api/passkeys/login/options');
    const credential = await navigator.credentials.get(
      { publicKey: /** @type {any} */ (requestOptions(options)) });
    return request('POST', '/api/passkeys/login', { credential: credentialJson(credential) });
  },
};
