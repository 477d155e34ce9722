"""`bench.fastfiz`: FastFiz's table in our engine, for `bench.ai --table fastfiz`.

FastFiz (`FastFiz.cpp`, its rail and pocket events) drops a ball the moment its edge
reaches a pocket's line: at a side pocket the rail's nose, between the two points of the
0.12 m opening; at a corner the line `x + y = 0.11/sqrt(2) + R` (south-west), whose ends
lie a ball's radius off each jaw point along its rail. Nothing rattles, nothing hangs.
A ball rolled alone is checked here against that line, found by hand: where the
rolling ball's travel at its pocket event puts its centre.
"""

import math

import numpy as np

from bench.ai import runout_position
from bench.fastfiz import FASTFIZ_LENGTH, FASTFIZ_WIDTH, MouthLineTable, fastfiz_table
from server.engine import MotionState, Table
from server.rules import ANYWHERE
from tests.support.rolling import DECEL, R, roll


def roll_at(table: Table, start: tuple[float, float], angle_deg: float, speed: float):
    """`roll` at `angle_deg`, far enough to reach any pocket here; returns the ball set,
    the events and the direction."""
    direction = (math.cos(math.radians(angle_deg)), math.sin(math.radians(angle_deg)))
    balls, events = roll(table, start, direction, speed, travel=1.0)
    return balls, events, direction


def centre_at_drop(start, direction, speed, events) -> tuple[float, float]:
    """Where the rolling ball's centre was at its pocket event (rolling: s = v t - a t^2/2)."""
    (drop,) = [e for e in events if e.kind == "pocket"]
    travel = speed * drop.time - DECEL * drop.time**2 / 2
    return start[0] + travel * direction[0], start[1] + travel * direction[1]


def test_the_table_is_fastfizs_size_and_mouths() -> None:
    table = fastfiz_table()
    assert isinstance(table, MouthLineTable)
    assert (table.length, table.width) == (FASTFIZ_LENGTH, FASTFIZ_WIDTH) == (2.236, 1.116)
    assert (table.corner_mouth, table.side_mouth) == (0.11, 0.12)


def test_a_ball_drops_in_the_side_pocket_as_its_edge_reaches_the_rails_nose() -> None:
    """At 45 degrees, 50 mm off the opening's middle: FastFiz drops it where its centre
    crosses y = R; our WPA side pocket of the same 120 mm (its points, facings and shelf)
    turns it away."""
    fastfiz = fastfiz_table()
    mid = fastfiz.length / 2
    for offset in (-0.05, 0.0, 0.05):
        cross = (mid + offset, R)  # where the centre reaches the rail's line
        start = (cross[0] - 0.4 / math.sqrt(2), cross[1] + 0.4 / math.sqrt(2))
        balls, events, direction = roll_at(fastfiz, start, -45.0, 1.5)
        assert balls.states[0] == MotionState.POCKETED, offset
        assert fastfiz.pockets[int(balls.pockets[0])].name == "bottom_side"
        assert not [e for e in events if e.kind in ("cushion", "jaw")], events
        x, y = centre_at_drop(start, direction, 1.5, events)
        assert abs(x - cross[0]) < 3e-4 and abs(y - cross[1]) < 3e-4, (offset, x, y)
    wpa = Table(fastfiz.length, fastfiz.width, corner_mouth=0.11, side_mouth=0.12)
    cross = (mid + 0.05, R)
    start = (cross[0] - 0.4 / math.sqrt(2), cross[1] + 0.4 / math.sqrt(2))
    balls, events, _ = roll_at(wpa, start, -45.0, 1.5)
    assert balls.states[0] != MotionState.POCKETED
    assert [e for e in events if e.kind == "jaw"]


def test_a_ball_beside_the_opening_meets_the_rail() -> None:
    """2 mm past the opening's point the same ball hits the cushion and stays up."""
    table = fastfiz_table()
    cross = (table.length / 2 + 0.06 + 0.002, R)
    start = (cross[0] - 0.4 / math.sqrt(2), cross[1] + 0.4 / math.sqrt(2))
    balls, events, _ = roll_at(table, start, -45.0, 1.5)
    assert balls.states[0] != MotionState.POCKETED
    assert [e.kind for e in events if e.kind != "rest"][:1] == ["cushion"]


def test_a_ball_drops_in_the_corner_as_it_crosses_the_corners_line() -> None:
    """Along the rail 1 mm off it, and straight at the corner from 30 mm off the middle:
    each drops where its centre reaches x + y = w/sqrt(2) + R, touching no point."""
    table = fastfiz_table()
    line = 0.11 / math.sqrt(2) + R
    along_rail = ((0.6, R + 0.001), 180.0)
    middle = np.array([line / 2, line / 2])
    across = np.array([1.0, -1.0]) / math.sqrt(2)
    straight_in = (tuple(middle + 0.03 * across + 0.5 * np.array([1.0, 1.0])), -135.0)
    for start, angle in (along_rail, straight_in):
        balls, events, direction = roll_at(table, start, angle, 2.0)
        assert balls.states[0] == MotionState.POCKETED, start
        assert table.pockets[int(balls.pockets[0])].name == "bottom_left"
        assert not [e for e in events if e.kind in ("cushion", "jaw")], events
        x, y = centre_at_drop(start, direction, 2.0, events)
        assert abs((x + y) - line) < 4e-4, (start, x + y, line)


def test_the_runouts_start_on_fastfizs_table() -> None:
    """`bench.ai --table fastfiz`: the rack is broken and run on FastFiz's table."""
    game = runout_position(3, np.random.default_rng(3 + 999), "fastfiz")
    assert isinstance(game.table, MouthLineTable)
    assert (game.turn, game.ball_in_hand, game.groups, game.over) == (1, ANYWHERE, None, False)
    for ball in game.balls.on_table_ids():
        x, y = game.balls.positions[game.balls.index(ball)]
        assert R <= x <= FASTFIZ_LENGTH - R and R <= y <= FASTFIZ_WIDTH - R, (ball, x, y)
