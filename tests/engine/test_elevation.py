"""The raised cue: the `Shot` contract, the miscue rule, and the strike's swerve and masse.

Model: Alciatore, TP A-30 (cue strike with an elevated cue), the model pooltool 0.6.0's
`theta` follows: the impulse along the cue's axis, spin r x J / I in three dimensions, the
downward part into the bed. The massé and swerve figures were measured with pooltool 0.6.0
(own virtualenv, default InstantaneousPoint strike, default parameters): a lone cue ball on
an 8 m x 8 m table (`PocketTableSpecs(l=8, w=8)`, no cushion in reach),
`system.strike(V0, phi=90, theta, a=-side, b=0)` with V0 chosen so that the ball leaves at
`speed x cos(theta)` along the bed (our `speed` is the ball's speed along the cue),
`pt.simulate`, `pt.continuize(dt=0.0002)`; the offset from the aim line, to the left
positive, at the first sample 1 m down the aim line.
"""

import hashlib
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from server.codec import from_data, from_json, to_data, to_json
from server.engine import (
    BALL_MASS,
    BALL_RADIUS,
    DEFAULT_PARAMS,
    MAX_ELEVATION,
    MAX_TIP,
    BallSet,
    Miscue,
    Shot,
    check_stroke,
    cue_offset,
    settle,
    simulate,
    step,
    strike,
    tip_seen_level,
)

TICK = 1 / 120
START = (0.3, 1.1)
# (elevation degrees, side along the cue, speed m/s) -> pooltool 0.6.0's offset (m) 1 m on.
POOLTOOL_OFFSET_AT_1M = {(60, 0.5, 2.0): -0.6814, (30, 0.5, 3.0): -0.0789, (15, 0.5, 2.0): -0.0624}
MASSE = (60, 0.5, 2.0)


def stroke(degrees: float, side: float, speed: float, angle: float = 0.0) -> Shot:
    elevation = math.radians(degrees)
    return Shot(angle, speed, tip_seen_level((side, 0.0), elevation), elevation)


def offset_down_the_line(table, shot: Shot, distance: float) -> float:
    """The ball's offset from its aim line (+x), to the left positive, when it first gets
    `distance` down the line (linear between the engine's ticks)."""
    result = simulate(table, BallSet.place({0: START}), shot)
    xy = np.vstack([START, result.frames.positions[:, 0]]) - START
    k = int(np.flatnonzero(xy[:, 0] >= distance)[0])
    f = (distance - xy[k - 1, 0]) / (xy[k, 0] - xy[k - 1, 0])
    return float(xy[k - 1, 1] + f * (xy[k, 1] - xy[k - 1, 1]))


# --- the contract ------------------------------------------------------------------------


def test_max_elevation_is_80_degrees():
    assert math.degrees(MAX_ELEVATION) == pytest.approx(80.0)


def test_a_level_shot_is_written_as_before_and_an_old_one_loads_level():
    assert to_data(Shot(1.5, 3.0, (0.1, -0.2))) == {"angle": 1.5, "speed": 3.0, "tip": [0.1, -0.2]}
    assert from_data(Shot, {"angle": 1.5, "speed": 3.0, "tip": [0.1, -0.2]}).elevation == 0.0


def test_a_raised_shot_round_trips_bit_for_bit():
    shot = Shot(0.3, 2.0, (0.5, 0.75), math.radians(60))
    assert to_data(shot)["elevation"] == math.radians(60)
    assert from_data(Shot, to_data(shot)) == shot
    assert from_json(Shot, to_json(shot)) == shot


@pytest.mark.parametrize("elevation", [-1e-9, MAX_ELEVATION * 1.0001, math.inf])
def test_an_elevation_out_of_bounds_is_refused(elevation: float):
    with pytest.raises(ValueError, match=r"elevation|finite"):
        Shot(0.0, 2.0, (0.0, 0.5), elevation)


@given(st.floats(-0.6, 0.6), st.floats(-0.6, 0.6))
def test_the_miscue_rule_is_the_plain_tip_bound_for_a_level_cue(side: float, height: float):
    if math.hypot(side, height) <= MAX_TIP:
        check_stroke((side, height), 0.0)
        assert cue_offset((side, height), 0.0) == pytest.approx(math.hypot(side, height), abs=1e-7)
    else:
        with pytest.raises(ValueError, match=r"within 0\.5"):
            check_stroke((side, height), 0.0)


def test_a_tip_below_centre_with_a_steep_cue_is_a_miscue():
    # 45 degrees at 0.3 R below centre: the contact normal is 63 degrees off the cue's axis.
    with pytest.raises(Miscue, match="strike higher on the ball"):
        Shot(0.0, 2.0, (0.0, -0.3), math.radians(45))
    assert cue_offset((0.0, -0.3), math.radians(45)) == pytest.approx(
        math.sin(math.radians(45) + math.asin(0.3))
    )
    # Level, the same tip is a draw shot.
    Shot(0.0, 2.0, (0.0, -0.3))


@settings(max_examples=60, deadline=None)
@given(
    st.floats(-MAX_TIP, MAX_TIP),
    st.floats(-MAX_TIP, MAX_TIP),
    st.floats(0.0, MAX_ELEVATION),
)
def test_every_tip_within_half_a_radius_seen_along_the_cue_is_playable(a, b, elevation):
    depth = math.sqrt(1 - a * a - b * b)
    if math.hypot(a, b) > MAX_TIP or math.cos(elevation) * depth < math.sin(elevation) * b:
        return  # off the disc, or a contact past the ball's top (no tip seen from behind)
    tip = tip_seen_level((a, b), elevation)
    assert cue_offset(tip, elevation) == pytest.approx(math.hypot(a, b), abs=1e-7)
    Shot(0.0, 1.0, tip, elevation)


# --- the strike ----------------------------------------------------------------------------


def test_a_raised_cue_sends_the_ball_at_speed_cos_elevation_with_the_same_squirt():
    shot = stroke(60, 0.5, 2.0)
    (vx, vy), _ = shot.cue_ball_motion(BALL_RADIUS)
    assert math.hypot(vx, vy) == pytest.approx(1.0)
    assert math.atan2(vy, vx) == pytest.approx(shot.squirt())
    assert shot.downward_speed() == pytest.approx(2.0 * math.sin(math.radians(60)))


def test_side_spin_with_elevation_tilts_the_spin_axis_forward():
    # r x J / I: a right-side hit pushed down spins the ball about its forward axis too.
    # pooltool 0.6.0, the same stroke: 75.77 rad/s about the forward axis, 43.74 about the
    # vertical, none about the side axis (the cue's axis passes over the centre). Ours
    # takes r x J for the squirted J, as the level strike does: a few % less.
    (_, _), (wx, wy, wz) = stroke(60, 0.5, 2.0).cue_ball_motion(BALL_RADIUS)
    assert wx == pytest.approx(75.77, rel=0.05)
    assert wz == pytest.approx(43.74, rel=0.05)
    assert abs(wy) < 0.1
    (_, _), (lx, _, _) = Shot(0.0, 2.0, (0.5, 0.0)).cue_ball_motion(BALL_RADIUS)
    assert abs(lx) < 1e-9


def test_a_60_degree_masse_curves_as_far_as_pooltools_within_a_quarter(table):
    offset = offset_down_the_line(table, stroke(*MASSE), 1.0)
    assert offset == pytest.approx(POOLTOOL_OFFSET_AT_1M[MASSE], rel=0.25)
    assert offset < 0.0  # right english squirts left, then curves back right past the line


@pytest.mark.parametrize("case", [(30, 0.5, 3.0), (15, 0.5, 2.0)])
def test_a_swerve_curves_the_same_way_as_pooltools_and_no_further(table, case):
    # Here the ball hops off the slate (pooltool 0.6.0 has no flight): no cloth touches it
    # in the air, so its swerve starts later and is smaller 1 m on, never larger.
    offset = offset_down_the_line(table, stroke(*case), 1.0)
    assert POOLTOOL_OFFSET_AT_1M[case] < offset < 0.0


def test_a_level_stroke_with_the_same_english_does_not_curve_back(table):
    # Without elevation the ball runs along its squirted line (left of the aim).
    assert offset_down_the_line(table, Shot(0.0, 2.0, (0.5, 0.0)), 1.0) > 0.0


def mechanical_energy(balls: BallSet) -> float:
    """With the height's potential energy: a flying ball trades one for the other."""
    return balls.mechanical_energy(BALL_MASS, BALL_RADIUS, DEFAULT_PARAMS.g)


@pytest.mark.parametrize("case", [(60, 0.5, 2.0), (80, -0.5, 4.0), (30, 0.3, 6.0)])
def test_energy_never_rises_after_a_raised_strike(table, case):
    balls = BallSet.place({0: START, 1: (1.5, 0.6), 2: (1.2, 0.3)})
    strike(balls, stroke(*case))
    energy = mechanical_energy(balls)
    for k in range(6000):
        step(table, balls, TICK, k * TICK)
        now = mechanical_energy(balls)
        assert now <= energy * (1 + 1e-12) + 1e-15
        energy = now
        if balls.at_rest():
            break
    assert balls.at_rest()


def digest(balls: BallSet) -> str:
    h = hashlib.sha256()
    arrays = (balls.positions, balls.velocities, balls.spins, balls.states, balls.heights)
    for array in (*arrays, balls.phases):
        h.update(np.ascontiguousarray(array).tobytes())
    return h.hexdigest()


def test_the_same_raised_shot_twice_is_bit_identical(table):
    balls = BallSet.place({0: START, 1: (1.5, 0.6), 2: (1.2, 0.3)})
    shot = stroke(60, -0.4, 3.0, angle=0.2)
    first, second = simulate(table, balls, shot), simulate(table, balls, shot)
    assert digest(first.final) == digest(second.final)
    assert np.array_equal(first.frames.positions, second.frames.positions)
    assert digest(settle(table, balls, shot).final) == digest(first.final)
