"""The carom table and its three balls: the UMB sizes and spots, no pockets, the engine's
facts (no overlap, on the bed, determinism, energy) on it, and its rails against pooltool.

POOLTOOL_* were measured with pooltool 0.6.0 (own virtualenv) by `python -m
bench.carom_rails`: its billiard table (`BilliardTableSpecs`: 2840 x 1420 mm, cushion
height 37 mm) and its BILLIARD_GENERIC ball (R 30.75 mm, 210 g, f_c 0.15), a single ball
given a rolling state 0.15 m before a rail, as `test_cushion.py` does for the pool table.
"""

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from server.engine import Shot, Table, rack, simulate
from server.engine.params import DEFAULT_PARAMS, params_for
from server.engine.rack import RED, WHITE, YELLOW
from server.engine.simulate import settle

from .conftest import bank, in_play_area, pair_min_gap
from .styled_tables import SHOTS, assert_energy_never_rises, placements

CAROM = Table.carom()
R = CAROM.ball_radius
TICK = 1 / 120

# Rolling ball straight into a rail: speed out / in (the same at 0.5, 1 and 2 m/s).
POOLTOOL_STRAIGHT_RATIO = 0.5019
# Rolling banks: angle out from the normal (degrees) for angle in, at 0.8 and 1.5 m/s.
POOLTOOL_BANK_OUT = {15: 22.80, 30: 44.39, 45: 62.56, 60: 75.86}
# 45 degree rolling bank at 1.5 m/s with side spin wz = 1.25 v / R: speed out / in.
POOLTOOL_RUNNING_RATIO = 0.8435
POOLTOOL_CHECK_RATIO = 0.6099


def test_the_umb_match_table_has_no_pockets_and_its_spots():
    assert (CAROM.length, CAROM.width) == (2.84, 1.42)
    assert pytest.approx(0.0615 / 2) == R
    assert CAROM.pockets == () and CAROM.jaws == ()
    assert len(CAROM.cushions) == 4
    spots = CAROM.spots
    assert spots["head"] == (0.71, 0.71) and spots["foot"] == (2.13, 0.71)
    assert spots["head"][1] - spots["break_right"][1] == pytest.approx(0.1825)


def test_carom_balls_and_cloth_are_pooltools_billiard_set_and_pool_is_unchanged():
    params = params_for(CAROM)
    assert (params.radius, params.mass) == (R, 0.210)
    assert params.cushion_nose == pytest.approx(0.037 / 0.0615)
    assert params.f_cushion == 0.15
    assert params_for(Table.pool("9ft")) is DEFAULT_PARAMS


def test_a_carom_table_round_trips_and_a_pool_shot_is_stored_as_before():
    from server.codec import from_data, to_data

    assert from_data(Table, to_data(CAROM)) == CAROM
    assert from_data(Table, CAROM.fields()) == CAROM
    assert to_data(Shot(0.1, 2.0)) == {"angle": 0.1, "speed": 2.0, "tip": [0.0, 0.0]}
    yellow = Shot(0.1, 2.0, ball=YELLOW)
    assert to_data(yellow)["ball"] == YELLOW
    assert from_data(Shot, to_data(yellow)) == yellow


def test_the_opening_position():
    balls = rack("three_cushion", CAROM)
    assert balls.ids.tolist() == [WHITE, YELLOW, RED]
    assert balls.position_of(RED) == CAROM.spots["foot"]
    assert balls.position_of(YELLOW) == CAROM.spots["head"]
    assert balls.position_of(WHITE) == CAROM.spots["break_right"]


def test_the_yellow_is_struck_when_the_shot_says_so():
    balls = rack("three_cushion", CAROM)
    result = simulate(CAROM, balls, Shot(math.pi / 2, 1.0, ball=YELLOW))
    assert result.events[0].ids == (YELLOW,)
    assert result.final.position_of(WHITE) == balls.position_of(WHITE)
    assert result.final.position_of(YELLOW) != balls.position_of(YELLOW)
    settled = settle(CAROM, balls, Shot(math.pi / 2, 1.0, ball=YELLOW))
    assert settled.contacts() == result.contacts()


@pytest.mark.parametrize("tip", [(0.0, 0.3), (0.4, 0.0), (-0.3, -0.3)])
def test_a_hard_shot_runs_without_overlap_on_the_bed_and_twice_the_same(tip):
    balls = rack("three_cushion", CAROM)
    rx, ry = balls.position_of(RED)
    cx, cy = balls.position_of(WHITE)
    shot = Shot(math.atan2(ry - cy, rx - cx) + 0.02, 8.0, tip)
    result = simulate(CAROM, balls, shot)
    again = simulate(CAROM, balls, shot)
    assert result.stalled_ticks == 0
    assert np.array_equal(result.frames.positions, again.frames.positions)
    frames = result.frames
    for k in range(len(frames)):
        assert pair_min_gap(frames.positions[k], frames.on_table[k], R) >= -1e-9
        assert in_play_area(CAROM, frames.positions[k]).all()
    assert result.final.on_table.all() and result.final.at_rest()
    assert sum(e.kind == "cushion" for e in result.events) >= 3


@settings(
    max_examples=20,
    deadline=None,
    suppress_health_check=[HealthCheck.filter_too_much, HealthCheck.too_slow],
)
@given(balls=placements(CAROM, st.just(3)), shot=SHOTS)
def test_kinetic_energy_never_increases_on_the_carom_table(balls, shot):
    assert_energy_never_rises(CAROM, balls, shot, ticks=6000)
    assert balls.on_table.all()


@pytest.mark.parametrize("speed", [0.5, 1.0, 2.0])
def test_a_rolling_ball_straight_into_a_carom_rail_comes_back_at_pooltools_speed(speed):
    speed_in, speed_out, angle = bank(CAROM, speed, 0)
    assert angle == pytest.approx(0.0, abs=1e-6)
    assert speed_out / speed_in == pytest.approx(POOLTOOL_STRAIGHT_RATIO, abs=0.01)


@pytest.mark.parametrize("speed", [0.8, 1.5])
@pytest.mark.parametrize("angle_in", [15, 30, 45, 60])
def test_carom_banks_leave_at_pooltools_angles(speed, angle_in):
    _, _, angle_out = bank(CAROM, speed, angle_in)
    assert angle_out == pytest.approx(POOLTOOL_BANK_OUT[angle_in], abs=0.5)


def test_running_and_check_english_off_a_carom_rail_as_pooltool():
    v = 1.5
    # Our bottom rail: a ball running +x along it has running english with wz < 0.
    speed_in, running, _ = bank(CAROM, v, 45, wz=-1.25 * v / R)
    _, check, _ = bank(CAROM, v, 45, wz=+1.25 * v / R)
    assert running / speed_in == pytest.approx(POOLTOOL_RUNNING_RATIO, abs=0.01)
    assert check / speed_in == pytest.approx(POOLTOOL_CHECK_RATIO, abs=0.01)
