"""Pockets: a mouth between two jaw points, angled facings, a shelf and the hole.

A ball drops when its centre is over the hole, not when it crosses the mouth line, so a
slow ball can hang on the shelf and a ball that catches a facing can rattle out.

POOLTOOL_* were measured with pooltool 0.6.0 (own virtualenv, default resolver and ball
parameters) on `pt.Table.from_table_specs(PocketTableSpecs(l=2.54, w=1.27,
corner_pocket_width=0.114, side_pocket_width=0.127))`, our table's size and mouths, with a
single ball given a rolling state 0.5 m from the middle of the mouth: the window is the
largest offset (mm, 1 mm steps, per side) across the line of approach at which the ball
still drops into that pocket within 0.8 m of rolling; the hanger figure is where the
fastest ball that stays comes to rest (bisection on the speed), measured past the mouth.
pooltool's side offsets are mirrored (its table is ours reflected), so pairs are compared
sorted. Our table's pocket jaws are sharp points, pooltool's are rounded (corner radius
21 mm), which is most of the difference along the rail.
"""

import math

import numpy as np
import pytest

from server.engine import MotionState
from tests.support.rolling import R, roll

from .conftest import in_play_area

POOLTOOL_CORNER_WINDOW = {0.6: 37, 1.5: 34, 4.0: 33}  # straight in, +- mm
POOLTOOL_RAIL_WINDOW = {0.6: 33, 1.5: 29, 4.0: 28}  # frozen to the rail, mm off it
POOLTOOL_SIDE_WINDOW = {
    90: {0.6: (43, 43), 1.5: (41, 41), 4.0: (40, 40)},
    60: {0.6: (32, 37), 1.5: (31, 34), 4.0: (31, 34)},
    30: {0.6: (6, 17), 1.5: (5, 16), 4.0: (5, 16)},
}
POOLTOOL_CORNER_HANGER_MM = 36.7  # rest point past the middle of the corner's mouth line
POOLTOOL_SIDE_HANGER_MM = 4.0  # past the side pocket's mouth line


def approach(table, pocket_name, angle_deg=None):
    """(middle of the mouth, unit direction of approach) for a pocket; for a side pocket
    `angle_deg` is the angle between the path and the rail."""
    pocket = next(p for p in table.pockets if p.name == pocket_name)
    mouth = (np.array(pocket.jaws[0]) + np.array(pocket.jaws[1])) / 2
    if angle_deg is None:
        return mouth, np.array(pocket.outward)
    a = math.radians(angle_deg)
    return mouth, np.array([-math.cos(a), -math.sin(a)])


def drops(table, pocket_name, mouth, direction, offset, speed, dist=0.5):
    across = np.array([-direction[1], direction[0]])
    balls, _ = roll(table, mouth - dist * direction + offset * across, direction, speed)
    index = next(k for k, p in enumerate(table.pockets) if p.name == pocket_name)
    return balls.states[0] == MotionState.POCKETED and balls.pockets[0] == index


def window(table, pocket_name, mouth, direction, speed, sign):
    """Largest offset (mm) on one side at which the ball still drops (1 mm steps)."""
    last, mm = 0, 0
    while mm <= 120 and mm <= last + 10:
        if drops(table, pocket_name, mouth, direction, sign * mm / 1000, speed):
            last = mm
        mm += 1
    return last


@pytest.mark.parametrize("speed", [0.6, 1.5, 4.0])
def test_straight_in_corner_window_is_pooltools(table, speed):
    mouth, u = approach(table, "bottom_left")
    half = window(table, "bottom_left", mouth, u, speed, +1)
    assert window(table, "bottom_left", mouth, u, speed, -1) == half
    # was +-50 mm at 0.6 m/s when a ball dropped at the mouth line
    assert half == pytest.approx(POOLTOOL_CORNER_WINDOW[speed], abs=4)


@pytest.mark.parametrize("speed", [0.6, 1.5, 4.0])
def test_along_the_rail_window(table, speed):
    # Frozen to the bottom rail, rolling into the bottom-left corner: how far off the rail.
    last = 0
    for mm in range(0, 80):
        start = np.array([0.5, R + mm / 1000])
        balls, _ = roll(table, start, np.array([-1.0, 0.0]), speed)
        if balls.states[0] == MotionState.POCKETED and balls.pockets[0] == 0:
            last = mm
        elif mm > last + 10:
            break
    # Sharp points against pooltool's rounded ones: within 5 mm.
    assert last == pytest.approx(POOLTOOL_RAIL_WINDOW[speed], abs=5)


@pytest.mark.parametrize("angle", [90, 60, 30])
@pytest.mark.parametrize("speed", [0.6, 1.5, 4.0])
def test_side_pocket_windows(table, angle, speed):
    mouth, d = approach(table, "bottom_side", angle)
    ours = sorted(window(table, "bottom_side", mouth, d, speed, s) for s in (+1, -1))
    theirs = sorted(POOLTOOL_SIDE_WINDOW[angle][speed])
    # At 30 degrees ours is stingier on the far side (10 mm against 16): our side facings
    # follow the WPA's 104 degrees where pooltool's are at 97, and our points are sharp
    # where pooltool's are rounded (8 mm); both let pooltool's ball slide in off the far
    # point.
    assert ours == pytest.approx(theirs, abs=7 if angle == 30 else 5)
    # the side pocket shrinks as the approach flattens (DA: side pockets "play stingy")
    if angle == 30:
        assert sum(ours) < 30


def hang(table, mouth, direction, dist=0.5):
    """Bisect the speed between staying and dropping: (rest point of the fastest ball
    that stays, its distance past the mouth line in mm, the slowest that drops)."""
    lo, hi = 0.1, 0.6
    keep = None
    for _ in range(30):
        mid = (lo + hi) / 2
        balls, _ = roll(table, mouth - dist * direction, direction, mid, travel=10.0)
        if balls.states[0] == MotionState.POCKETED:
            hi = mid
        else:
            lo, keep = mid, balls.positions[0].copy()
    assert keep is not None
    return keep, float((keep - mouth) @ direction) * 1000


def test_a_slow_ball_hangs_on_a_corner_pockets_shelf(table):
    mouth, u = approach(table, "bottom_left")
    rest, past = hang(table, mouth, u)
    pocket = table.pockets[0]
    # It stops past the mouth line, on the shelf, and stays on the table: a hanger.
    assert past == pytest.approx(pocket.shelf * 1000, abs=0.5)
    assert past == pytest.approx(POOLTOOL_CORNER_HANGER_MM, abs=2.5)
    assert 19 <= past <= 51  # real shelves (Roger Long's survey: 3/4 to 2 in)
    assert in_play_area(table, rest)[0]


def test_a_slow_ball_hangs_in_a_side_pocket(table):
    mouth, d = approach(table, "bottom_side", 90)
    rest, past = hang(table, mouth, d)
    assert 0 < past == pytest.approx(table.pockets[1].shelf * 1000, abs=0.5)
    assert past == pytest.approx(POOLTOOL_SIDE_HANGER_MM, abs=2.5)
    assert past <= 9.525  # WPA side shelf 0 to 3/8 in
    assert in_play_area(table, rest)[0]


def test_a_ball_into_the_facing_rattles(table):
    # Just outside the straight-in corner window at medium speed: it catches a facing and
    # the other, and stays out.
    mouth, u = approach(table, "bottom_left")
    across = np.array([-u[1], u[0]])
    rattles = 0
    for mm in range(20, 60, 2):
        _balls, events = roll(table, mouth - 0.5 * u + mm / 1000 * across, u, 1.5)
        jaws = [e for e in events if e.kind == "jaw"]
        if len(jaws) >= 2:
            rattles += 1
        assert {e.target for e in jaws} <= {0, 11}  # this pocket's two jaws only
    assert rattles >= 3
