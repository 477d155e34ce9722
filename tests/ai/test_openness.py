"""How open the table is for a player's balls (`geometry.open_share`): a ball counts by how
pottable it is, not by a clear line to a pocket alone."""

from __future__ import annotations

from server.ai.geometry import open_share
from server.engine import BallSet

from .conftest import TABLE, R, straight_line

ON_RAIL = (TABLE.length - R, 0.4)  # frozen on the foot rail, 0.4 m from the lower corner


def test_a_ball_near_a_pocket_in_the_open_is_fully_open() -> None:
    obj, _ = straight_line(3, 0.5, 0.0)
    balls = BallSet.place({0: (0.6, 0.6), 11: obj})
    assert open_share(TABLE, balls, [11]) == 1.0


def test_a_rail_ball_is_open_until_a_ball_is_frozen_beside_it() -> None:
    alone = BallSet.place({0: (0.6, 0.6), 11: ON_RAIL})
    assert open_share(TABLE, alone, [11]) == 1.0  # along the rail into either corner
    # A ball frozen beside it on the rail: the way along the rail is shut, and the cue ball
    # would have to come from where that ball lies to pot it anywhere else.
    beside = BallSet.place({0: (0.6, 0.6), 11: ON_RAIL, 5: (ON_RAIL[0], ON_RAIL[1] + 2 * R)})
    assert open_share(TABLE, beside, [11]) < 0.2
    assert open_share(TABLE, beside, [5, 11]) < 0.6


def test_a_ball_in_a_cluster_is_not_open() -> None:
    x, y = TABLE.length * 0.7, TABLE.width / 2
    d = 2 * R + 1e-4
    cluster = {3: (x, y), 4: (x + d, y), 5: (x - d, y), 6: (x, y + d), 7: (x, y - d)}
    near_pocket, _ = straight_line(0, 0.5, 0.0)
    balls = BallSet.place({0: (0.6, 0.6), 9: near_pocket, **cluster})
    assert open_share(TABLE, balls, [3]) == 0.0
    assert open_share(TABLE, balls, [3, 9]) == 0.5  # the mean over the balls


def test_balls_with_a_clear_line_but_no_way_in_are_not_open() -> None:
    """A traced runout's last two stripes (seed 301): each has a clear line to a pocket,
    so a clear line alone counted the table fully open, yet no cue-ball position on the
    bed reaches either: the 9 lies beside the 6 and behind the 3, the 11 by the foot rail
    between the 6 and the 7 with the 4 in the corner. The runout ended there on a
    safety."""
    spots = {
        0: (0.333, 0.9),
        1: (1.373, 0.087),
        2: (1.623, 0.55),
        3: (2.417, 0.463),
        4: (2.505, 1.235),
        5: (1.877, 1.237),
        6: (2.43, 0.68),
        7: (2.453, 1.113),
        8: (1.6, 0.327),
        9: (2.357, 0.693),
        11: (2.493, 0.967),
    }
    balls = BallSet.place(spots)
    assert open_share(TABLE, balls, [9, 11]) < 0.2
