"""Each stored shot against the pro level's best choice from the same table.

The pro plans the position (`Bot.plan`, seeded from the match and shot ids), then its best
stroke and the stroke played are valued on the same noisy draws of the pro's execution
error (`Search.score_noisy`: the rules judge each draw, the table it leaves is scored), so
the two values differ by the choice alone, never by luck. The played stroke is the one
stored: for a person the stroke as sent, for the computer the stroke its arm played.
Deterministic: the same match gives the same analysis on any machine and any run.
"""

from __future__ import annotations

import zlib
from dataclasses import dataclass, replace

import numpy as np

from server.engine import CUE, BallSet, Shot
from server.rules import Game

from ..bot import Bot, Turn, still_racked
from ..levels import BY_NAME
from ..search import Candidate, Search
from .rebuild import Before, StoredShot, positions
from .verdicts import Judged, accuracy, loss_of, turning_points, verdict

LEVEL = "pro"
DRAWS = 64  # noisy draws each of the two strokes is valued on
SALT = 0xA7A1  # keeps the analysis' draws apart from the rooms' own seeds


def shot_seed(match_id: int, n: int) -> int:
    """The pro's seed for shot `n` of match `match_id` (its plan there is then fixed)."""
    return zlib.crc32(f"analysis:{match_id}:{n}".encode())


@dataclass(frozen=True)
class BestShot:
    """The pro's choice: what it tries, the stroke, where it puts the cue ball with ball in
    hand, its chance (share of the draws that pocket legally) and value (-1..+1: the
    position it leaves, on average over the draws)."""

    kind: str  # pot | safety | kick | break | push
    target: int | None
    pocket: int | None
    via: str | None
    call: int | None
    angle: float
    speed: float
    tip: tuple[float, float]
    place: tuple[float, float] | None
    chance: float
    value: float


@dataclass(frozen=True)
class ShotVerdict:
    """One shot judged. loss: the winning chance given away against the best (0-1)."""

    n: int
    game: int
    seat: int
    verdict: str  # best | good | mistake | blunder
    loss: float
    played_chance: float
    played_value: float
    best: BestShot
    ball_in_hand: str | None
    push_out: bool


@dataclass(frozen=True)
class PlayerSummary:
    seat: int
    name: str
    accuracy: float | None  # 0-100; None: no shot of theirs
    best: int
    good: int
    mistakes: int
    blunders: int


@dataclass(frozen=True)
class MatchAnalysis:
    match_id: int
    kind: str
    level: str
    players: list[PlayerSummary]
    shots: list[ShotVerdict]
    turning_points: list[int]  # shot numbers, in match order


def analyse_match(
    match_id: int,
    kind: str,
    players: list[str],
    shots: list[StoredShot],
    budget: int | None = None,
) -> MatchAnalysis:
    """Every shot of a stored match judged, and the players' accuracy. `budget`: the pro's
    simulations per plan (None: the pro's own)."""
    judged = [judge_shot(match_id, before, budget) for before in positions(kind, players, shots)]
    return summarise(match_id, kind, players, judged)


def summarise(
    match_id: int, kind: str, players: list[str], judged: list[ShotVerdict]
) -> MatchAnalysis:
    """The match's analysis from its shots judged one by one (`judge_shot`)."""
    light = [Judged(s.n, s.seat, s.loss) for s in judged]
    summaries = [_summary(seat, name, judged, light) for seat, name in enumerate(players)]
    return MatchAnalysis(match_id, kind, LEVEL, summaries, judged, turning_points(light))


def _summary(seat: int, name: str, judged: list[ShotVerdict], light: list[Judged]) -> PlayerSummary:
    mine = [s.verdict for s in judged if s.seat == seat]
    return PlayerSummary(
        seat,
        name,
        accuracy(light, seat),
        mine.count("best"),
        mine.count("good"),
        mine.count("mistake"),
        mine.count("blunder"),
    )


def judge_shot(match_id: int, before: Before, budget: int | None = None) -> ShotVerdict:
    """The pro's best choice from the table before the shot, both strokes valued."""
    stored, game = before.stored, before.game
    bot = Bot(LEVEL, seed=shot_seed(match_id, stored.n))
    if budget is not None:
        bot.level = replace(bot.level, budget=budget)
    turn = bot.plan(_for_plan(game), stored.seat)
    assert turn.shot is not None
    search = _search(game, stored.seat, np.random.default_rng([match_id, stored.n, SALT]))
    balls = game.balls
    best_balls = balls.with_ball(CUE, turn.place) if turn.place is not None else balls
    best = _valued(search, best_balls, turn.shot, turn.call, turn.kind or "pot")
    played = _valued(search, balls, before.stroke, before.call, "played")
    loss = loss_of(best.value, played.value)
    return ShotVerdict(
        n=stored.n,
        game=stored.game,
        seat=stored.seat,
        verdict=verdict(loss),
        loss=loss,
        played_chance=played.pot_rate,
        played_value=played.value,
        best=_best(turn, best),
        ball_in_hand=game.ball_in_hand,
        push_out=before.push_out,
    )


def _for_plan(game: Game) -> Game:
    """The game as the pro plans it: a declared push out stays declared, never offered."""
    if game.push_out_declared:
        game.push_out_available = False
    return game


def _search(game: Game, seat: int, rng: np.random.Generator) -> Search:
    """A search of the pro's level over `DRAWS` draws of its execution error."""
    pos = game.position()
    if not pos.breaking and still_racked(game.rules, game.balls, game.table):
        pos = replace(pos, breaking=True)
    noise = rng.standard_normal((DRAWS, 4))
    return Search(game.table, game.rules, pos, seat, BY_NAME[LEVEL], noise, noise[:0])


def _valued(search: Search, balls: BallSet, shot: Shot, call: int | None, kind: str) -> Candidate:
    cand = Candidate(shot, call, kind)
    search.score_noisy(balls, cand)
    return cand


def _best(turn: Turn, valued: Candidate) -> BestShot:
    shot = turn.shot
    assert shot is not None
    return BestShot(
        kind=turn.kind or "pot",
        target=turn.target,
        pocket=turn.pocket,
        via=turn.via,
        call=turn.call,
        angle=shot.angle,
        speed=shot.speed,
        tip=(float(shot.tip[0]), float(shot.tip[1])),
        place=turn.place,
        chance=valued.pot_rate,
        value=valued.value,
    )
