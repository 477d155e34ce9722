"""Builders for the computer-opponent tests: games set on constructed tables."""

from __future__ import annotations

import math

import pytest

from server.engine import BallSet, MotionState, Table
from server.rules import Game

TABLE = Table.pool("9ft")
R = TABLE.ball_radius


def pocket_aim(index: int) -> tuple[float, float]:
    (ax, ay), (bx, by) = TABLE.pockets[index].jaws
    return ((ax + bx) / 2, (ay + by) / 2)


def straight_line(
    pocket: int, object_from_pocket: float, cue_behind: float
) -> tuple[tuple[float, float], tuple[float, float]]:
    """An object ball `object_from_pocket` m from pocket `pocket`'s mouth on the line to the
    table's centre, and the cue ball `cue_behind` m further along the same line."""
    px, py = pocket_aim(pocket)
    cx, cy = TABLE.length / 2, TABLE.width / 2
    d = math.hypot(cx - px, cy - py)
    ux, uy = (cx - px) / d, (cy - py) / d
    obj = (px + ux * object_from_pocket, py + uy * object_from_pocket)
    cue = (obj[0] + ux * cue_behind, obj[1] + uy * cue_behind)
    return obj, cue


def set_table(
    game: Game,
    placement: dict[int, tuple[float, float]],
    turn: int = 0,
    groups: dict[int, str] | None = None,
    ball_in_hand: str | None = None,
) -> Game:
    """`game` after its break with exactly `placement` on the table (the other balls of its
    set pocketed), `turn` to shoot."""
    full = {b: (0.1 + 0.1 * b, 0.1) for b in game.balls.ids.tolist()}
    full.update(placement)
    balls = BallSet.place(full)
    for b in full:
        if b not in placement:
            row = balls.index(b)
            balls.states[row] = MotionState.POCKETED
            balls.pockets[row] = 0
            balls.positions[row] = TABLE.pockets[0].center
    game.balls = balls
    game.breaking = False
    game.turn = turn
    game.groups = groups
    game.ball_in_hand = ball_in_hand
    game.decision = game.pending = None
    return game


@pytest.fixture
def eight() -> Game:
    return Game.new("eight_ball", ["ana", "bot"], seed=3)


@pytest.fixture
def nine() -> Game:
    return Game.new("nine_ball", ["ana", "bot"], seed=3)
