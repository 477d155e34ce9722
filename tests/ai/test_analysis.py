"""The analysis of a stored match: the same every run, the pro's own choice judged best,
a stroke away from every ball a blunder."""

from __future__ import annotations

import math

from server.ai.analysis import analyse_match
from server.codec import to_data
from tests.support.analysis import (
    KIND,
    PLAYERS,
    away_from_every_ball,
    club_game,
    pros_choice,
)

MATCH_ID = 41


def test_the_same_match_gives_the_same_analysis() -> None:
    shots = list(club_game())[:4]
    first = analyse_match(MATCH_ID, KIND, PLAYERS, shots)
    again = analyse_match(MATCH_ID, KIND, PLAYERS, shots)
    assert to_data(first) == to_data(again)
    assert [s.n for s in first.shots] == [s.n for s in shots]
    assert all(s.verdict in ("best", "good", "mistake", "blunder") for s in first.shots)
    for player in first.players:
        assert player.accuracy is None or 0.0 <= player.accuracy <= 100.0


def test_the_pros_own_choice_is_judged_best() -> None:
    shots = list(club_game())[:3]
    shots[2] = pros_choice(MATCH_ID, shots, 3)
    judged = analyse_match(MATCH_ID, KIND, PLAYERS, shots).shots[2]
    assert judged.verdict == "best"
    assert judged.loss == 0.0
    assert math.isclose(judged.played_chance, judged.best.chance)


def test_a_stroke_away_from_every_ball_is_a_blunder() -> None:
    shots = list(club_game())[:3]
    shots[2] = away_from_every_ball(shots, 3)
    analysis = analyse_match(MATCH_ID, KIND, PLAYERS, shots)
    judged = analysis.shots[2]
    assert judged.verdict == "blunder"
    assert judged.played_chance == 0.0
    assert 3 in analysis.turning_points
