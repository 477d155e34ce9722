/**
 * Watching a finished match again (`/m/{match_id}`).
 *
 * Each stored shot starts from the table as it was before it (`shots[k].b`); the server
 * simulates it again from its stored start state and streams it like the live one
 * (`GET /api/matches/{id}/shots/{n}/replay`, one JSON message a line, paced at the chosen
 * speed). The messages go through the live table's reducer and the shared shot playback
 * (frames, sounds, pocketed balls), so a replay looks and sounds exactly like the game did.
 * The stream's tick rate comes with the match (`stream`). Shots follow each other while
 * playing; Stop puts the shot back at its start; previous/next move by one shot.
 */

import { api, memory, readNdjson } from '../net.js';
import { initialState, reduce, decodeBalls } from '../state.js';
import { readStream } from '../limits.js';
import { ShotPlayback } from '../playback.js';
import { CELS } from '../sprites.js';
import { drawBalls, drawSinking, drawCue } from '../render.js';
import { DEFAULT_LIMITS } from '../limits.js';
import { TableAudio } from '../audio.js';
import { TableCanvas } from '../tablecanvas.js';
import { $, $select, bindMute, setText, matchLine } from '../ui.js';
import { startLoop } from '../loop.js';

const PAUSE_BETWEEN_SHOTS = 0.8; // seconds the table rests before the next shot plays

/** @param {string} matchId */
export function startReplay(matchId) {
  $('replay').hidden = false;
  document.title = 'Pool online · replay';
  const surface = new TableCanvas(/** @type {HTMLCanvasElement} */ ($('replay-table')),
    $('replay-wrap'));
  const audio = new TableAudio();
  audio.setMuted(memory.muted());
  const playback = new ShotPlayback({ cels: CELS, delay: 0.1,
    onSound: (sound, speed) => audio.play(sound, speed) });
  /** @type {any} the match detail (`GET /api/matches/{id}`) */
  let match = null;
  let stream = readStream(null); // the pacing of the stored shots' stream
  let index = 0;
  let playing = false;
  let speed = 1;
  /** @type {{abort: AbortController, done: boolean, outcome: string} | null} */
  let shotStream = null; // the shot being streamed
  let generation = 0;
  /** @type {number | null} when the current shot finished playing */
  let restSince = null;
  let state = initialState({ stream });
  let struck = false; // the shot shown has started moving (the cue is drawn until then)

  /** @param {string} text */
  const showError = (text) => {
    const el = $('replay-error');
    el.textContent = text;
    el.hidden = !text;
  };
  const playButton = $('replay-play');
  const showPlaying = () => { playButton.textContent = playing ? 'Stop' : 'Play'; };

  async function load() {
    try {
      match = await api.getMatch(matchId);
    } catch (e) {
      const err = /** @type {import('../net.js').ApiError} */ (e);
      setText($('replay-title'), 'Replay');
      showError(err.status === 404 || err.status === 422 ? 'There is no such match.'
        : `Cannot load the match: ${err.message}`);
      return;
    }
    stream = readStream(match.stream);
    const game = match.game === 'nine_ball' ? '9-ball' : '8-ball';
    setText($('replay-title'), `${(match.players ?? []).join(' vs ')} · ${game}`);
    const won = match.winner_name ? ` · ${match.winner_name} won` : '';
    setText($('replay-score'), `${matchLine(match)}${won}`);
    if (!match.shots.length || !match.geometry) {
      showError('This match has no shots to watch.');
      return;
    }
    playback.setTable(match.geometry);
    show(0);
  }

  function stopStream() {
    generation += 1;
    shotStream?.abort.abort();
    shotStream = null;
  }

  /**
   * Put shot k's starting table on the cloth; stream it when playing.
   * @param {number} k
   */
  function show(k) {
    if (!match?.shots.length) return;
    stopStream();
    index = Math.min(match.shots.length - 1, Math.max(0, k));
    const shot = match.shots[index];
    state = initialState({ stream });
    restSince = null;
    playback.reset(decodeBalls(shot.b));
    setText($('replay-shot'), `shot ${index + 1} / ${match.shots.length}`);
    const players = match.players ?? [];
    setText($('replay-shooter'), `${players[shot.seat] ?? `Player ${shot.seat + 1}`} to play`);
    setText($('replay-at'), `game ${shot.game} · ${scoreBefore(match, shot)}`);
    struck = false;
    setText($('replay-outcome'), '');
    if (playing) play(shot);
  }

  /** @param {{replay: string, outcome?: {message?: string}}} shot */
  async function play(shot) {
    const mine = generation;
    const abort = new AbortController();
    const current = { abort, done: false, outcome: shot.outcome?.message ?? '' };
    shotStream = current;
    try {
      const res = await fetch(`${shot.replay}?pace=${speed}`, { signal: abort.signal });
      if (!res.ok) throw new Error(`the server answered ${res.status}`);
      await readNdjson(res, (msg) => { if (mine === generation) receive(msg); });
      if (mine === generation) current.done = true;
    } catch (e) {
      if ((e instanceof Error && e.name === 'AbortError') || mine !== generation) return;
      showError(`Cannot replay this shot: ${e instanceof Error ? e.message : String(e)}`);
      playing = false;
      showPlaying();
    }
  }

  /** @param {Record<string, any>} msg */
  function receive(msg) {
    const now = performance.now() / 1000;
    if (msg.type === 'shot_result') {
      if (shotStream) shotStream.outcome = msg.outcome?.message ?? shotStream.outcome;
      return;
    }
    const res = reduce(state, msg, now);
    state = res.state;
    for (const e of res.effects) {
      if (e.kind === 'frame') struck = true;
      playback.apply(e, now);
    }
  }

  /**
   * @param {number} dt
   * @param {number} now
   */
  function update(dt, now) {
    playback.update(dt, now, speed);
    if (!playing || !shotStream?.done || !playback.done) return;
    if (restSince === null) {
      restSince = now;
      setText($('replay-outcome'), shotStream.outcome);
    } else if (now - restSince > PAUSE_BETWEEN_SHOTS / speed) {
      if (index + 1 < match.shots.length) show(index + 1);
      else { playing = false; showPlaying(); }
    }
  }

  /** @param {number} now */
  function draw(now) {
    if (!surface.layout(match?.geometry)) return;
    const ctx = surface.begin();
    const { view, sprites, dpr } = surface;
    if (!sprites) return;
    drawBalls(ctx, view, sprites, playback.balls, 1 / dpr);
    for (const s of playback.sinking.list) drawSinking(ctx, view, sprites, s, now, 1 / dpr);
    // The cue, as it was lined up for the shot, until the cue ball moves.
    const shot = match?.shots[index];
    const cueBall = playback.balls.get(0);
    struck = struck || playback.framesSeen > 0;
    if (!struck && shot?.shot && cueBall) {
      const power = Math.min(1, (shot.shot.speed ?? 0) / DEFAULT_LIMITS.max_speed);
      drawCue(ctx, view, match.geometry, [cueBall.x, cueBall.y], shot.shot.angle, power * 0.5);
    }
  }

  playButton.addEventListener('click', () => {
    audio.unlock();
    if (!match?.shots.length) return;
    playing = !playing;
    showPlaying();
    if (playing) {
      const atEnd = shotStream?.done && playback.done;
      show(atEnd && index + 1 < match.shots.length ? index + 1 : index);
    } else show(index);
  });
  $('replay-prev').addEventListener('click', () => show(index - 1));
  $('replay-next').addEventListener('click', () => show(index + 1));
  $('replay-speed').addEventListener('change', () => {
    speed = Number($select('replay-speed').value) || 1;
    if (playing) show(index);
  });
  bindMute($('replay-mute'), audio, (muted) => memory.setMuted(muted));
  startLoop((dt, now) => { update(dt, now); draw(now); });
  load();

  /**
   * "Ana 1 – 0 Ben": the score when stored shot `shot` was played (games won before its game).
   * @param {any} m the match
   * @param {any} shot
   */
  function scoreBefore(m, shot) {
    const players = m.players ?? [];
    const won = [0, 1].map((seat) => (m.games ?? []).filter((/** @type {any} */ g) =>
      g.n < shot.game && g.winner === seat).length);
    return `${players[0] ?? '?'} ${won[0]} – ${won[1]} ${players[1] ?? '?'}`;
  }

  // Read-only hook for automated tests and debugging.
  /** @type {any} */ (window).__replay = {
    get match() { return match; },
    get index() { return index; },
    get playing() { return playing; },
    get framesSeen() { return playback.framesSeen; },
    get balls() {
      return [...playback.balls].map(([id, b]) => ({ id, x: b.x, y: b.y, cel: b.cel }));
    },
    get ready() { return !!(surface.view && surface.sprites); },
    get cueDrawn() { return !struck; },
  };
}
