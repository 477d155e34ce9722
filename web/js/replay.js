/**
 * Watching a finished match again (`/m/{match_id}`).
 *
 * Each stored shot starts from the table as it was before it (`shots[k].b`); the server
 * simulates it again from its stored start state and streams it like the live one
 * (`GET /api/matches/{id}/shots/{n}/replay`, one JSON message a line, paced at the chosen
 * speed). The messages go through the live table's reducer, frame player, sprites and
 * sounds, so a replay looks and sounds exactly like the game did. Shots follow each other
 * while playing; Stop puts the shot back at its start; previous/next move by one shot.
 */

import { api, memory, readNdjson } from './net.js';
import { initialState, reduce, decodeBalls } from './state.js';
import { FramePlayer } from './interpolation.js';
import { CELS } from './sprites.js';
import { drawBalls } from './render.js';
import { TableAudio } from './audio.js';
import { TableCanvas } from './tablecanvas.js';
import { $, bindMute, setText, matchLine } from './ui.js';
import { startLoop } from './loop.js';

const PAUSE_BETWEEN_SHOTS = 0.8; // seconds the table rests before the next shot plays

export function startReplay(matchId) {
  $('replay').hidden = false;
  document.title = 'Pool online · replay';
  const surface = new TableCanvas($('replay-table'), $('replay-wrap'));
  const player = new FramePlayer({ cels: CELS, delay: 0.1 });
  const audio = new TableAudio();
  audio.setMuted(memory.muted());
  let match = null;
  let index = 0;
  let playing = false;
  let speed = 1;
  let stream = null; // {abort, done, generation} of the shot being streamed
  let generation = 0;
  let restSince = null; // when the current shot finished playing
  let state = initialState();
  let sounds = [];
  let balls = new Map();
  let framesSeen = 0;

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
      setText($('replay-title'), 'Replay');
      showError(e.status === 404 || e.status === 422 ? 'There is no such match.'
        : `Cannot load the match: ${e.message}`);
      return;
    }
    setText($('replay-title'), `${(match.players ?? []).join(' vs ')} · ${match.game === 'nine_ball' ? '9-ball' : '8-ball'}`);
    setText($('replay-score'), `${matchLine(match)}${match.winner_name ? ` · ${match.winner_name} won` : ''}`);
    if (!match.shots.length || !match.geometry) {
      showError('This match has no shots to watch.');
      return;
    }
    player.radius = match.geometry.ball_radius;
    show(0);
  }

  function stopStream() {
    generation += 1;
    stream?.abort.abort();
    stream = null;
  }

  /** Put shot k's starting table on the cloth; stream it when playing. */
  function show(k) {
    if (!match?.shots.length) return;
    stopStream();
    index = Math.min(match.shots.length - 1, Math.max(0, k));
    const shot = match.shots[index];
    state = { ...initialState(), tickHz: 120 };
    sounds = [];
    restSince = null;
    player.reset(decodeBalls(shot.b));
    balls = player.current;
    setText($('replay-shot'), `shot ${index + 1} / ${match.shots.length}`);
    setText($('replay-outcome'), '');
    if (playing) play(shot);
  }

  async function play(shot) {
    const mine = generation;
    const abort = new AbortController();
    stream = { abort, done: false, outcome: shot.outcome?.message ?? '' };
    try {
      const res = await fetch(`${shot.replay}?pace=${speed}`, { signal: abort.signal });
      if (!res.ok) throw new Error(`the server answered ${res.status}`);
      await readNdjson(res, (msg) => { if (mine === generation) receive(msg, shot); });
      if (mine === generation) stream.done = true;
    } catch (e) {
      if (e.name === 'AbortError' || mine !== generation) return;
      showError(`Cannot replay this shot: ${e.message}`);
      playing = false;
      showPlaying();
    }
  }

  function receive(msg, shot) {
    const now = performance.now() / 1000;
    if (msg.type === 'shot_result') {
      if (stream) stream.outcome = msg.outcome?.message ?? stream.outcome;
      return;
    }
    const res = reduce(state, msg, now);
    state = res.state;
    for (const e of res.effects) {
      if (e.kind === 'shot') player.startShot(decodeBalls(shot.b), 0);
      else if (e.kind === 'frame') {
        framesSeen += 1;
        player.push({ t: e.t, balls: e.balls, last: e.last, ahead: e.ahead });
      } else if (e.kind === 'sound') sounds.push({ ...e, at: now });
    }
  }

  function update(dt, now) {
    balls = player.advance(dt * speed);
    for (let i = 0; i < sounds.length; i++) {
      const s = sounds[i];
      if (!player.playing || s.t <= player.time + 0.01 || now - s.at > 0.6 / speed) {
        audio.play(s.sound, s.speed);
        sounds.splice(i, 1);
        i--;
      }
    }
    if (!playing || !stream?.done || !player.done) return;
    if (restSince === null) {
      restSince = now;
      setText($('replay-outcome'), stream.outcome);
    } else if (now - restSince > PAUSE_BETWEEN_SHOTS / speed) {
      if (index + 1 < match.shots.length) show(index + 1);
      else { playing = false; showPlaying(); }
    }
  }

  function draw() {
    if (!surface.layout(match?.geometry)) return;
    const ctx = surface.begin();
    if (surface.sprites) drawBalls(ctx, surface.view, surface.sprites, balls, 1 / surface.dpr);
  }

  playButton.addEventListener('click', () => {
    audio.unlock();
    if (!match?.shots.length) return;
    playing = !playing;
    showPlaying();
    if (playing) {
      const atEnd = stream?.done && player.done;
      show(atEnd && index + 1 < match.shots.length ? index + 1 : index);
    } else show(index);
  });
  $('replay-prev').addEventListener('click', () => show(index - 1));
  $('replay-next').addEventListener('click', () => show(index + 1));
  $('replay-speed').addEventListener('change', (ev) => {
    speed = Number(ev.target.value) || 1;
    if (playing) show(index);
  });
  bindMute($('replay-mute'), audio, (muted) => memory.setMuted(muted));
  startLoop((dt, now) => { update(dt, now); draw(); });
  load();

  // Read-only hook for automated tests and debugging.
  window.__replay = {
    get match() { return match; },
    get index() { return index; },
    get playing() { return playing; },
    get framesSeen() { return framesSeen; },
    get balls() { return [...balls].map(([id, b]) => ({ id, x: b.x, y: b.y, cel: b.cel })); },
    get ready() { return !!(surface.view && surface.sprites); },
  };
}
