"""The snooker table and its 22 balls: the WPBSA's sizes and spots, and the engine's facts
(no overlap, on the bed, determinism, energy) on it.

POOLTOOL_* were measured with pooltool 0.6.0 (own virtualenv) by `python -m bench.pockets`:
its "Generic Snooker" pockets (openings 83 and 75 mm, rounded jaws of 91 and 63.5 mm
radius, pocket depths 36 and 24 mm, radii 43 and 42.7 mm) on a 3569 x 1778 mm table with
pooltool's snooker ball (R 26.19 mm), a single ball given a rolling state 0.5 m before the
middle of the mouth: the window is the largest offset (mm, 1 mm steps, per side) across the
line of approach at which it still drops into that pocket. Ours are measured the same way
(`tests.support.rolling`).
"""

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from server.engine import MotionState, Shot, Table, rack, simulate
from server.engine.params import params_for
from server.engine.rack import COLOURS, REDS
from tests.support.rolling import roll

from .conftest import in_play_area, pair_min_gap
from .styled_tables import SHOTS, assert_energy_never_rises, placements

SNOOKER = Table.snooker()
R = SNOOKER.ball_radius
TICK = 1 / 120

POOLTOOL_CORNER_WINDOW = {0.6: 26, 1.5: 25, 4.0: 22}  # straight in, +- mm
POOLTOOL_SIDE_WINDOW = {90: (44, 44), 60: (33, 42)}  # at 1.5 m/s, mm each side


def test_the_wpbsa_playing_area_balls_and_markings():
    # WPBSA 1.1 The Standard Table, 1.2 Balls: 3569 x 1778 mm, 52.5 mm balls, baulk line 737 mm,
    # D radius 292 mm, black spot 324 mm from the top cushion.
    assert (SNOOKER.length, SNOOKER.width) == (3.569, 1.778)
    assert SNOOKER.ball_radius == 0.02625
    assert SNOOKER.head_string == 0.737
    spots = SNOOKER.spots
    mid = SNOOKER.width / 2
    assert spots["brown"] == (0.737, mid)
    assert spots["yellow"] == pytest.approx((0.737, mid - 0.292))
    assert spots["green"] == pytest.approx((0.737, mid + 0.292))
    assert spots["blue"] == (SNOOKER.length / 2, mid)
    assert spots["pink"] == (SNOOKER.length * 3 / 4, mid)
    assert spots["black"] == pytest.approx((SNOOKER.length - 0.324, mid))
    assert SNOOKER.in_d(0.737, mid + 0.292) and SNOOKER.in_d(0.5, mid)
    assert not SNOOKER.in_d(0.74, mid) and not SNOOKER.in_d(0.5, mid + 0.3)
    assert params_for(SNOOKER).radius == R
    assert [a.radius for a in SNOOKER.arcs] == [0.292]


def test_a_snooker_table_round_trips_and_pool_tables_are_stored_as_before():
    from server.codec import from_data, to_data

    assert to_data(SNOOKER)["style"] == "snooker"
    assert from_data(Table, to_data(SNOOKER)) == SNOOKER
    assert from_data(Table, SNOOKER.fields()) == SNOOKER
    assert "style" not in to_data(Table.pool("9ft"))
    assert len(Table.pool("9ft").fields()) == 5


def test_the_rack_is_22_balls_in_place_without_overlap():
    balls = rack("snooker", SNOOKER, seed=3)
    assert balls.ids.tolist() == list(range(22))
    assert pair_min_gap(balls.positions, balls.on_table, R) >= 0
    for name, ball in COLOURS.items():
        assert balls.position_of(ball) == SNOOKER.spots[name]
    reds = np.array([balls.position_of(b) for b in REDS])
    pink_x = SNOOKER.spots["pink"][0]
    # WPBSA 3.2 Position of Balls: the apex red as near the pink as possible without touching it.
    assert reds[:, 0].min() - pink_x == pytest.approx(2 * R, abs=1e-4)
    assert SNOOKER.in_d(*balls.position_of(0))
    assert in_play_area(SNOOKER, balls.positions).all()


def test_the_break_runs_without_overlap_on_the_bed_and_twice_the_same():
    balls = rack("snooker", SNOOKER, seed=0)
    cx, cy = balls.position_of(0)
    rx, ry = balls.position_of(15)  # a red at the back corner of the triangle
    shot = Shot(math.atan2(ry - cy, rx - cx) - 0.01, 7.0, (0.0, 0.2))
    result = simulate(SNOOKER, balls, shot)
    again = simulate(SNOOKER, balls, shot)
    assert result.stalled_ticks == 0
    assert np.array_equal(result.final.positions, again.final.positions)
    assert np.array_equal(result.frames.positions, again.frames.positions)
    frames = result.frames
    for k in range(len(frames)):
        on = frames.on_table[k]
        assert pair_min_gap(frames.positions[k], on, R) >= -1e-9
        assert in_play_area(SNOOKER, frames.positions[k][on]).all()
    assert result.final.at_rest()


@settings(
    max_examples=20,
    deadline=None,
    suppress_health_check=[HealthCheck.filter_too_much, HealthCheck.too_slow],
)
@given(balls=placements(SNOOKER, st.integers(2, 6)), shot=SHOTS)
def test_kinetic_energy_never_increases_on_the_snooker_table(balls, shot):
    assert_energy_never_rises(SNOOKER, balls, shot, ticks=4000)


def _drops(name, start, direction, speed):
    balls, _ = roll(SNOOKER, start, direction, speed)
    index = next(k for k, p in enumerate(SNOOKER.pockets) if p.name == name)
    return balls.states[0] == MotionState.POCKETED and balls.pockets[0] == index


def _window(name, direction, speed, sign):
    """Largest offset (mm) on one side of the mouth's middle at which the ball drops."""
    pocket = next(p for p in SNOOKER.pockets if p.name == name)
    mouth = (np.array(pocket.jaws[0]) + np.array(pocket.jaws[1])) / 2
    across = np.array([-direction[1], direction[0]])
    last, mm = 0, 0
    while mm <= 120 and mm <= last + 10:
        if _drops(name, mouth - 0.5 * direction + sign * mm / 1000 * across, direction, speed):
            last = mm
        mm += 1
    return last


@pytest.mark.parametrize("speed", [0.6, 1.5, 4.0])
def test_the_corner_accepts_what_pooltools_snooker_corner_accepts(speed):
    u = np.array(SNOOKER.pockets[0].outward)
    half = _window("bottom_left", u, speed, +1)
    assert _window("bottom_left", u, speed, -1) == half
    assert half == pytest.approx(POOLTOOL_CORNER_WINDOW[speed], abs=4)
    # Far narrower than the pool table's corner (+-37 mm at 0.6 m/s): a snooker pocket
    # is barely wider than two balls.
    assert half < 30


@pytest.mark.parametrize("angle", [90, 60])
def test_the_middle_pocket_accepts_what_pooltools_accepts(angle):
    a = math.radians(angle)
    d = np.array([-math.cos(a), -math.sin(a)])
    ours = sorted(_window("bottom_side", d, 1.5, s) for s in (+1, -1))
    # Within 6 mm: our jaws are sharp points, pooltool's rounded (63.5 mm).
    assert ours == pytest.approx(sorted(POOLTOOL_SIDE_WINDOW[angle]), abs=6)
