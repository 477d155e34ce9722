/**
 * Talking to the server: the HTTP API (rooms) and the room WebSocket with automatic
 * reconnection (exponential back-off, capped). Messages go out as JSON objects; incoming
 * ones are parsed (the binary `motion` message decoded by track.js) and handed to
 * `onMessage`. See docs/protocol.md.
 */

import { decodeMotion } from './track.js';

/** An HTTP API error: the server's message, status and error code. */
export class ApiError extends Error {
  /**
   * @param {string} message
   * @param {number} status
   * @param {string | null} code
   */
  constructor(message, status, code) {
    super(message);
    this.status = status;
    this.code = code;
  }
}

/**
 * @param {string} method
 * @param {string} path
 * @param {object} [body]
 * @returns {Promise<any>}
 */
export async function request(method, path, body) {
  const res = await fetch(path, {
    method,
    headers: body ? { 'Content-Type': 'application/json' } : {},
    body: body ? JSON.stringify(body) : undefined,
  });
  let data;
  try { data = await res.json(); } catch { data = null; }
  if (!res.ok) {
    const d = data?.detail;
    const message = (d && typeof d === 'object' && !Array.isArray(d) && d.message)
      || (Array.isArray(d) && d[0]?.msg) || `HTTP ${res.status}`;
    throw new ApiError(message, res.status, d?.code ?? null);
  }
  return data;
}

export const api = {
  /**
   * @param {string} game
   * @param {number} raceTo
   * @param {number} [shotClock]
   * @param {boolean} [listed] false: a private table, reached only through its link
   * @param {string} [opponent] the computer's level, to play it in the second seat
   * @param {boolean} [ranked] a ranked table: rated when both players agree
   */
  createRoom: (game, raceTo, shotClock, listed = true, opponent = undefined, ranked = false) =>
    request('POST', '/api/rooms', { game, race_to: raceTo, listed,
      ...(shotClock !== undefined ? { shot_clock: shotClock } : {}),
      ...(opponent ? { opponent } : {}), ...(ranked ? { ranked } : {}) }),
  computerLevels: () => request('GET', '/api/computer'),
  listRooms: () => request('GET', '/api/rooms'),
  /** @param {string} roomId */
  getRoom: (roomId) => request('GET', `/api/rooms/${encodeURIComponent(roomId)}`),
  /**
   * @param {string} roomId
   * @param {string} name
   * @param {boolean} [ranked] agree that a ranked table changes your rating
   */
  join: (roomId, name, ranked = false) =>
    request('POST', `/api/rooms/${encodeURIComponent(roomId)}/join`,
      { name, ...(ranked ? { ranked } : {}) }),
  finishedMatches: (limit = 10) => request('GET', `/api/matches?status=finished&limit=${limit}`),
  /** @param {string} matchId */
  getMatch: (matchId) => request('GET', `/api/matches/${encodeURIComponent(matchId)}`),
  /** The server's limits (as in `welcome`), for forms shown before any room is joined. */
  limits: () => request('GET', '/api/limits'),
};

/**
 * Read a newline-delimited JSON response (a shot's replay) and hand each message to
 * `onMessage` as it arrives; resolves when the stream ends (rejects if it is aborted).
 * @param {Response} response
 * @param {(msg: any) => void} onMessage
 */
export async function readNdjson(response, onMessage) {
  if (!response.body) return;
  const reader = response.body.getReader();
  const decoder = new TextDecoder();
  let buffered = '';
  for (;;) {
    const { value, done } = await reader.read();
    buffered += decoder.decode(value ?? new Uint8Array(), { stream: !done });
    let newline;
    while ((newline = buffered.indexOf('\n')) >= 0) {
      const line = buffered.slice(0, newline).trim();
      buffered = buffered.slice(newline + 1);
      if (line) onMessage(JSON.parse(line));
    }
    if (done) break;
  }
  if (buffered.trim()) onMessage(JSON.parse(buffered));
}

/** Close codes after which reconnecting cannot help. */
const FINAL_CLOSE = new Set([4000]);

export class RoomSocket {
  /**
   * @param {string} roomId
   * @param {() => string|null} getToken the seat token (null: spectator), read at each connect
   * @param {object} handlers
   * @param {(msg: Record<string, any>) => void} handlers.onMessage
   * @param {(status: string, detail?: string) => void} handlers.onStatus
   */
  constructor(roomId, getToken, { onMessage, onStatus }) {
    this.roomId = roomId;
    this.getToken = getToken;
    this.onMessage = onMessage;
    this.onStatus = onStatus;
    /** @type {WebSocket | null} */
    this.ws = null;
    this.attempt = 0;
    this.closed = false;
    /** @type {ReturnType<typeof setTimeout> | undefined} */
    this.timer = undefined;
    this.refusals = 0;
    /** @type {string | null} the room's `ws_url`: where it is played now */
    this.wsUrl = null;
  }

  url() {
    const token = this.getToken();
    const q = token ? `?token=${encodeURIComponent(token)}` : '';
    if (this.wsUrl) return `${this.wsUrl}${q}`;
    const proto = location.protocol === 'https:' ? 'wss:' : 'ws:';
    return `${proto}//${location.host}/ws/rooms/${encodeURIComponent(this.roomId)}${q}`;
  }

  /**
   * Connect where the room is played now: its `ws_url` is asked before every (re)connect,
   * since after a server failed or was replaced another one plays the room.
   */
  connect() {
    if (this.closed) return;
    api.getRoom(this.roomId)
      .then((room) => { if (typeof room?.ws_url === 'string') this.wsUrl = room.ws_url; })
      .catch(() => {}) // unreachable or gone: try the last known address; the socket says why
      .finally(() => this.open());
  }

  open() {
    if (this.closed) return;
    this.onStatus(this.attempt === 0 ? 'connecting' : 'reconnecting');
    let opened = false;
    const ws = new WebSocket(this.url());
    ws.binaryType = 'arraybuffer'; // a shot's `motion` message
    this.ws = ws;
    ws.onopen = () => { opened = true; this.attempt = 0; this.refusals = 0; };
    ws.onmessage = (ev) => {
      let msg;
      try {
        msg = typeof ev.data === 'string' ? JSON.parse(ev.data) : decodeMotion(ev.data);
      } catch { return; }
      if (msg && typeof msg === 'object') {
        if (msg.type === 'welcome') this.onStatus('open');
        this.onMessage(msg);
      }
    };
    ws.onclose = (ev) => {
      if (this.ws !== ws) return;
      this.ws = null;
      if (this.closed) return;
      if (FINAL_CLOSE.has(ev.code)) { this.onStatus('closed', 'Opened in another tab.'); return; }
      if (!opened) this.refusals += 1;
      if (this.refusals >= 6) { this.onStatus('closed', 'The room cannot be reached.'); return; }
      this.attempt += 1;
      const wait = Math.min(8000, 400 * 2 ** Math.min(this.attempt - 1, 5));
      this.onStatus('reconnecting', `Reconnecting in ${Math.round(wait / 100) / 10} s`);
      this.timer = setTimeout(() => this.connect(), wait);
    };
  }

  /**
   * Send a message; returns false when not connected (the caller may retry).
   * @param {Record<string, any>} msg
   * @returns {boolean}
   */
  send(msg) {
    if (!this.ws || this.ws.readyState !== WebSocket.OPEN) return false;
    this.ws.send(JSON.stringify(msg));
    return true;
  }

  /** Reconnect now (e.g. after the token changed). */
  reconnect() {
    clearTimeout(this.timer);
    const old = this.ws;
    this.ws = null;
    if (old) old.close();
    this.attempt = 0;
    this.connect();
  }

  close() {
    this.closed = true;
    clearTimeout(this.timer);
    if (this.ws) this.ws.close(1000);
  }
}

// ---- remembered things ----------------------------------------------------------------
const store = globalThis.localStorage;

/** @typedef {{seat: number, token: string, name: string}} SeatTicket */

export const memory = {
  /** @returns {string} */
  name: () => store?.getItem('pool.name') ?? '',
  /** @param {string} n */
  setName: (n) => store?.setItem('pool.name', n),
  /** A name typed in the lobby and not yet saved to the profile (saved on the next page). */
  pendingName: () => store?.getItem('pool.pendingName') ?? '',
  /** @param {string} n '' once saved */
  setPendingName: (n) => (n ? store?.setItem('pool.pendingName', n)
    : store?.removeItem('pool.pendingName')),
  muted: () => store?.getItem('pool.muted') === '1',
  /** @param {boolean} m */
  setMuted: (m) => store?.setItem('pool.muted', m ? '1' : '0'),
  /**
   * {seat, token, name} for a room, or null.
   * @param {string} roomId
   * @returns {SeatTicket | null}
   */
  seat: (roomId) => {
    try { return JSON.parse(store?.getItem(`pool.seat.${roomId}`) ?? 'null'); } catch { return null; }
  },
  /**
   * @param {string} roomId
   * @param {SeatTicket} seat
   */
  setSeat: (roomId, seat) => store?.setItem(`pool.seat.${roomId}`, JSON.stringify(seat)),
};
