"""The jump shot at snooker, judged on real engine shots: WPBSA Section 2 Definitions,
"Jump Shot" (the cue ball passes over any part of an object ball, except over another ball
after first striking one), a foul under Section 3 Rule 11 Penalty Values (the value of the
ball on, at least 4). Stroke parameters that really jump: docs/engine.md (cue elevation)
and `tests/engine/test_jump.py`; on the snooker table's smaller balls the same strokes clear
a ball 20 cm ahead."""

import math

import numpy as np

from server.engine import Shot, simulate, tip_seen_level
from server.rules import Game
from server.rules.jumps import MARGIN

from .test_snooker import BLACK, MID, SNOOKER, frame

CUE = (1.0, MID)
RED = 1
R = SNOOKER.ball_radius


def raised(degrees: float, speed: float, angle: float = 0.0, side: float = 0.0) -> Shot:
    """A stroke with the cue raised `degrees`, its tip `side` (fraction of R) off centre."""
    elevation = math.radians(degrees)
    return Shot(angle, speed, tip_seen_level((side, 0.0), elevation), elevation)


def played(game: Game, shot: Shot):
    result = simulate(SNOOKER, game.balls, shot)
    return game.apply(0, result), result


def nearest_in_plan(result, ball: int) -> float:
    """The least plan-view distance between the cue ball's and `ball`'s centres."""
    rows = list(result.ids)
    gap = result.frames.positions[:, rows.index(0)] - result.frames.positions[:, rows.index(ball)]
    return float(np.hypot(gap[:, 0], gap[:, 1]).min())


def cue_touched(result, ball: int) -> bool:
    return any(e.kind == "ball" and set(e.ids) == {0, ball} for e in result.events)


def test_a_jump_over_a_ball_in_the_way_into_the_ball_on_is_a_foul_worth_the_ball_on():
    # WPBSA 2 "Jump Shot" and 3.11 Penalty Values: the cue ball passes over the black, 20
    # cm ahead, and hits the red on first; the foul costs the value of the ball on, 4 (the
    # black jumped over is not a ball involved: it was neither hit, potted nor forced off).
    game = frame({0: CUE, BLACK: (1.2, MID), RED: (2.5, MID)})
    out, result = played(game, raised(40, 5.0))
    assert result.first_contact() == RED and not cue_touched(result, BLACK)
    assert [f.code for f in out.fouls] == ["jump_shot"]
    assert out.fouls[0].message == "Ana's cue ball jumped over the black: a jump shot."
    assert game.points == (0, 4)
    assert game.decision is not None and game.decision.seat == 1


def test_over_another_ball_after_first_striking_the_ball_on_is_no_jump_shot():
    # WPBSA 2 "Jump Shot", its exception: the cue ball first strikes one object ball (the
    # red, in the air) and then jumps over another (the black, nearly over its centre).
    game = frame({0: CUE, RED: (2.0, MID + 0.03), BLACK: (2.106, 0.779)})
    out, result = played(game, raised(45, 4.0))
    assert result.first_contact() == RED and not cue_touched(result, BLACK)
    assert nearest_in_plan(result, BLACK) < 2 * R - MARGIN  # it did pass over the black
    assert not out.fouls and game.points == (0, 0)


def test_a_level_stroke_into_the_ball_in_the_way_is_the_wrong_ball_first():
    # WPBSA 2.15, 3.11: a level cue hits the black first (the ball on a red): worth the
    # black's 7, and no jump shot.
    game = frame({0: CUE, BLACK: (1.2, MID), RED: (2.5, MID)})
    out, result = played(game, Shot(0.0, 5.0))
    assert result.first_contact() == BLACK
    assert "wrong_ball_first" in [f.code for f in out.fouls]
    assert "jump_shot" not in [f.code for f in out.fouls]
    assert game.points == (0, 7)


def test_a_swerve_round_a_ball_in_the_way_is_legal():
    # WPBSA 2 "Jump Shot": a raised cue with side (a swerve; the ball hops off the slate,
    # then curves on the bed) that goes round the black, never over it, and hits the red.
    game = frame({0: CUE, BLACK: (1.5, MID), RED: (2.0, MID)})
    out, result = played(game, raised(45, 2.5, angle=0.2, side=0.5))
    assert result.first_contact() == RED
    assert nearest_in_plan(result, BLACK) > 2 * R
    assert not out.fouls and out.pocketed == (RED,)  # it pots the red, too
    assert game.points == (1, 0) and out.continues
