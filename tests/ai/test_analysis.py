"""The analysis of a stored match: the same every run, the pro's own choice judged best,
a stroke away from every ball a blunder."""

from __future__ import annotations

import dataclasses
import math
from functools import cache

from server.ai import Bot
from server.ai.analysis import LEVEL, StoredShot, analyse_match, positions, shot_seed
from server.ai.analysis.selfplay import self_play
from server.codec import to_data
from server.engine import CUE, BallSet, Shot, Table, simulate
from server.rules.shotfacts import shot_facts

MATCH_ID = 41
PLAYERS = ["Ana", "Ben"]


@cache
def stored_game() -> tuple[StoredShot, ...]:
    """A fixed game of 8-ball between two club players, as the history stores it."""
    return tuple(self_play("eight_ball", ("club", "club"), seed=5)[:6])


def test_the_same_match_gives_the_same_analysis() -> None:
    shots = list(stored_game())
    first = analyse_match(MATCH_ID, "eight_ball", PLAYERS, shots)
    again = analyse_match(MATCH_ID, "eight_ball", PLAYERS, shots)
    assert to_data(first) == to_data(again)
    assert [s.n for s in first.shots] == [s.n for s in shots]
    assert all(s.verdict in ("best", "good", "mistake", "blunder") for s in first.shots)
    for player in first.players:
        assert player.accuracy is None or 0.0 <= player.accuracy <= 100.0


def _with_stroke(stored: StoredShot, stroke: Shot, balls: BallSet) -> StoredShot:
    return dataclasses.replace(stored, shot=to_data(stroke), balls=balls.to_dict())


def test_the_pros_own_choice_is_judged_best() -> None:
    shots = list(stored_game())
    n = 3
    before = list(positions("eight_ball", PLAYERS, shots))[n - 1]
    turn = Bot(LEVEL, seed=shot_seed(MATCH_ID, n)).plan(before.game, before.stored.seat)
    assert turn.shot is not None
    balls = before.game.balls
    if turn.place is not None:
        balls = balls.with_ball(CUE, turn.place)
    shots[n - 1] = _with_stroke(shots[n - 1], turn.shot, balls)
    judged = analyse_match(MATCH_ID, "eight_ball", PLAYERS, shots[:n]).shots[n - 1]
    assert judged.verdict == "best"
    assert judged.loss == 0.0
    assert math.isclose(judged.played_chance, judged.best.chance)


def _away_from_every_ball(table: Table, balls: BallSet) -> Shot:
    """A firm stroke whose cue ball touches no other ball."""
    for k in range(72):
        shot = Shot(2 * math.pi * k / 72, 1.5)
        if shot_facts(balls, simulate(table, balls, shot)).first_contact is None:
            return shot
    raise AssertionError("every direction hits a ball")


def test_a_stroke_away_from_every_ball_is_a_blunder() -> None:
    shots = list(stored_game())
    n = 3
    before = list(positions("eight_ball", PLAYERS, shots))[n - 1]
    stroke = _away_from_every_ball(before.game.table, before.game.balls)
    shots[n - 1] = _with_stroke(shots[n - 1], stroke, before.game.balls)
    analysis = analyse_match(MATCH_ID, "eight_ball", PLAYERS, shots[:n])
    judged = analysis.shots[n - 1]
    assert judged.verdict == "blunder"
    assert judged.played_chance == 0.0
    assert n in analysis.turning_points
