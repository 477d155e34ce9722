/**
 * Watching a finished match again (`/m/{match_id}`).
 *
 * Each stored shot starts from the table as it was before it (`shots[k].b`); the server
 * simulates it again from its stored start state and streams it like the live one
 * (`GET /api/matches/{id}/shots/{n}/replay`, one JSON message a line, paced at the chosen
 * speed). The messages go into the live table's view (tableview.js: its reducer, its shot
 * playback with frames, sounds and pocketed balls, its drawing), so a replay looks and
 * sounds exactly like the game did. The stream's tick rate comes with the match (`stream`).
 * Shots follow each other while playing; Stop puts the shot back at its start;
 * previous/next move by one shot. "Analyse" shows the match's analysis (analysis.js): the
 * verdict strip, the accuracy per player, and the pro's best shot drawn over the table
 * beside the cue as it was lined up for the shot played.
 */

import { api, memory, readNdjson } from '../net.js';
import { initialState, decodeBalls } from '../state.js';
import { readStream, DEFAULT_LIMITS } from '../limits.js';
import { drawCue } from '../render.js';
import { drawPlan } from '../hint.js';
import { ReplayAnalysis } from '../analysis.js';
import { TableView } from '../tableview.js';
import { $, $select, bindMute, setText, matchLine } from '../ui.js';
import { startLoop } from '../loop.js';

const PAUSE_BETWEEN_SHOTS = 0.8; // seconds the table rests before the next shot plays

/** @param {string} matchId */
export function startReplay(matchId) {
  $('replay').hidden = false;
  document.title = 'Pool online · replay';
  const replay = new Replay(matchId);
  bindReplayControls(replay);
  startLoop((dt, now) => {
    replay.update(dt, now);
    replay.draw(now);
  });
  replay.load().then(() => {
    if (new URLSearchParams(location.search).get('analyse') === '1') replay.analysis.start();
  });
  /** @type {any} */ (window).__replay = testHook(replay);
}

/** @param {Replay} replay */
function bindReplayControls(replay) {
  $('replay-play').addEventListener('click', () => replay.toggle());
  $('replay-prev').addEventListener('click', () => replay.show(replay.index - 1));
  $('replay-next').addEventListener('click', () => replay.show(replay.index + 1));
  $('replay-speed').addEventListener('change', () => {
    replay.setSpeed(Number($select('replay-speed').value) || 1);
  });
  bindMute($('replay-mute'), replay.view.audio, (muted) => memory.setMuted(muted));
}

/**
 * Read-only hook for automated tests and debugging.
 * @param {Replay} replay
 */
function testHook(replay) {
  return {
    get match() { return replay.match; },
    get index() { return replay.index; },
    get playing() { return replay.playing; },
    get framesSeen() { return replay.view.playback.framesSeen; },
    get balls() { return replay.view.ballList(); },
    get ready() { return replay.view.ready; },
    get cueDrawn() { return !replay.struck; },
    get analysis() {
      const { data } = replay.analysis;
      return { ready: Boolean(data), verdicts: data?.shots.map((s) => s.verdict) ?? [],
        shot: replay.analysis.current(), bestDrawn: replay.bestDrawn };
    },
  };
}

/**
 * A finished match on the table view: `load`, then `show` a shot (streamed when playing);
 * the display loop calls `update` (the playback, the next shot after a pause) and `draw`.
 */
class Replay {
  /** @param {string} matchId */
  constructor(matchId) {
    this.matchId = matchId;
    this.stream = readStream(null); // the pacing of the stored shots' stream
    this.view = new TableView(/** @type {HTMLCanvasElement} */ ($('replay-table')),
      $('replay-wrap'), initialState({ stream: this.stream }));
    /** @type {any} the match detail (`GET /api/matches/{id}`) */
    this.match = null;
    this.index = 0;
    this.playing = false;
    this.speed = 1;
    /** @type {{abort: AbortController, done: boolean, outcome: string} | null} */
    this.shotStream = null; // the shot being streamed
    this.generation = 0;
    /** @type {number | null} when the current shot finished playing */
    this.restSince = null;
    this.struck = false; // the shot shown has started moving (the cue is drawn until then)
    this.playButton = $('replay-play');
    this.analysis = new ReplayAnalysis(matchId, (n) => {
      const k = this.match?.shots.findIndex((/** @type {any} */ s) => s.n === n) ?? -1;
      if (k >= 0) this.show(k);
    });
    this.bestDrawn = false; // the pro's best shot was drawn over the shot shown
  }

  async load() {
    try {
      this.match = await api.getMatch(this.matchId);
    } catch (e) {
      const err = /** @type {import('../net.js').ApiError} */ (e);
      setText($('replay-title'), 'Replay');
      showError(err.status === 404 || err.status === 422 ? 'There is no such match.'
        : `Cannot load the match: ${err.message}`);
      return;
    }
    const { match } = this;
    this.stream = readStream(match.stream);
    const game = { nine_ball: '9-ball', snooker: 'Snooker', three_cushion: 'Three-cushion' }[/** @type {string} */ (match.game)]
      ?? '8-ball';
    setText($('replay-title'), `${(match.players ?? []).join(' vs ')} · ${game}`);
    const won = match.winner_name ? ` · ${match.winner_name} won` : '';
    setText($('replay-score'), `${matchLine(match)}${won}`);
    if (!match.shots.length || !match.geometry) {
      showError('This match has no shots to watch.');
      return;
    }
    this.view.playback.setTable(match.geometry);
    this.show(0);
  }

  showPlaying() { this.playButton.textContent = this.playing ? 'Stop' : 'Play'; }

  /** Play or Stop. */
  toggle() {
    this.view.audio.unlock();
    if (!this.match?.shots.length) return;
    this.playing = !this.playing;
    this.showPlaying();
    if (this.playing) {
      const atEnd = this.shotStream?.done && this.view.playback.done;
      this.show(atEnd && this.index + 1 < this.match.shots.length ? this.index + 1 : this.index);
    } else this.show(this.index);
  }

  /** @param {number} speed */
  setSpeed(speed) {
    this.speed = speed;
    if (this.playing) this.show(this.index);
  }

  stopStream() {
    this.generation += 1;
    this.shotStream?.abort.abort();
    this.shotStream = null;
  }

  /**
   * Put shot k's starting table on the cloth; stream it when playing.
   * @param {number} k
   */
  show(k) {
    const { match } = this;
    if (!match?.shots.length) return;
    this.stopStream();
    this.index = Math.min(match.shots.length - 1, Math.max(0, k));
    const shot = match.shots[this.index];
    this.view.state = initialState({ stream: this.stream });
    this.restSince = null;
    this.view.playback.reset(decodeBalls(shot.b));
    setText($('replay-shot'), `shot ${this.index + 1} / ${match.shots.length}`);
    const players = match.players ?? [];
    setText($('replay-shooter'), `${players[shot.seat] ?? `Player ${shot.seat + 1}`} to play`);
    setText($('replay-at'), `game ${shot.game} · ${scoreBefore(match, shot)}`);
    this.struck = false;
    this.bestDrawn = false;
    this.analysis.select(shot.n);
    setText($('replay-outcome'), '');
    if (this.playing) this.play(shot);
  }

  /** @param {{replay: string, outcome?: {message?: string}}} shot */
  async play(shot) {
    const mine = this.generation;
    const abort = new AbortController();
    const current = { abort, done: false, outcome: shot.outcome?.message ?? '' };
    this.shotStream = current;
    try {
      const res = await fetch(`${shot.replay}?pace=${this.speed}`, { signal: abort.signal });
      if (!res.ok) throw new Error(`the server answered ${res.status}`);
      await readNdjson(res, (msg) => { if (mine === this.generation) this.receive(msg); });
      if (mine === this.generation) current.done = true;
    } catch (e) {
      if ((e instanceof Error && e.name === 'AbortError') || mine !== this.generation) return;
      showError(`Cannot replay this shot: ${e instanceof Error ? e.message : String(e)}`);
      this.playing = false;
      this.showPlaying();
    }
  }

  /** @param {Record<string, any>} msg */
  receive(msg) {
    const now = performance.now() / 1000;
    if (msg.type === 'shot_result') {
      if (this.shotStream) this.shotStream.outcome = msg.outcome?.message ?? this.shotStream.outcome;
      return;
    }
    this.view.play(this.view.receive(msg, now), now);
  }

  /**
   * @param {number} dt
   * @param {number} now
   */
  update(dt, now) {
    this.view.update(dt, now, this.speed);
    if (!this.playing || !this.shotStream?.done || !this.view.playback.done) return;
    if (this.restSince === null) {
      this.restSince = now;
      setText($('replay-outcome'), this.shotStream.outcome);
    } else if (now - this.restSince > PAUSE_BETWEEN_SHOTS / this.speed) {
      if (this.index + 1 < this.match.shots.length) this.show(this.index + 1);
      else { this.playing = false; this.showPlaying(); }
    }
  }

  /** @param {number} now */
  draw(now) {
    const { match, view } = this;
    const frame = view.begin(match?.geometry);
    if (!frame) return;
    view.drawBalls(frame, now);
    // The cue, as it was lined up for the shot, until the cue ball moves.
    const shot = match.shots[this.index];
    const cueBall = view.playback.balls.get(0);
    this.struck = this.struck || view.playback.framesSeen > 0;
    if (!this.struck && shot?.shot && cueBall) {
      const power = Math.min(1, (shot.shot.speed ?? 0) / DEFAULT_LIMITS.max_speed);
      drawCue(frame.ctx, frame.view, match.geometry, [cueBall.x, cueBall.y], shot.shot.angle,
        power * 0.5);
      const best = this.analysis.best();
      if (best) {
        drawPlan(frame.ctx, frame.view, match.geometry, view.ballList(), [cueBall.x, cueBall.y],
          DEFAULT_LIMITS, best, 0.35);
        this.bestDrawn = true;
      }
    }
  }
}

/** @param {string} text */
function showError(text) {
  const el = $('replay-error');
  el.textContent = text;
  el.hidden = !text;
}

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
