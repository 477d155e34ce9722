"""Han & Zhu (2004)'s two formulas on hand-made cases (§1 eq. 5, §2 eqs. 6-10)."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from server.engine import MotionState, PhysicsParams
from server.engine.physics.detect import line_contact_time, quadratic_contact_time
from server.engine.physics.resolve import ball_ball

R = 0.028575
# Han & Zhu's (2004) balls: elastic and frictionless (§1), so no throw.
ELASTIC = PhysicsParams(e_ball=1.0, u_ball_a=0.0, u_ball_b=0.0).array()


def collide(p1, p2, v1, v2, params=ELASTIC):
    pos = np.array([p1, p2], dtype=float)
    vel = np.array([v1, v2], dtype=float)
    w = np.zeros((2, 3))
    states = np.full(2, MotionState.SLIDING, dtype=np.int64)
    speed = ball_ball(pos, vel, w, states, 0, 1, params)
    return vel, speed


def test_head_on_exchanges_velocities():
    vel, speed = collide((0, 0), (2 * R, 0), (1.5, 0), (0, 0))
    assert vel[0] == pytest.approx([0, 0], abs=1e-15)
    assert vel[1] == pytest.approx([1.5, 0])
    assert speed == pytest.approx(1.5)


def test_normal_exchanged_tangential_kept_at_an_angle():
    a = math.radians(35)
    n = np.array([math.cos(a), math.sin(a)])
    t = np.array([-n[1], n[0]])
    v1 = 1.0 * n * -1 + 0.4 * t  # ball 1 sits along +n from ball 2 and moves back into it
    v2 = 0.3 * n - 0.2 * t
    p2 = np.zeros(2)
    p1 = p2 + 2 * R * n
    vel, _ = collide(p1, p2, v1, v2)
    assert vel[0] @ n == pytest.approx(v2 @ n)  # normals swapped
    assert vel[1] @ n == pytest.approx(v1 @ n)
    assert vel[0] @ t == pytest.approx(v1 @ t)  # tangentials kept
    assert vel[1] @ t == pytest.approx(v2 @ t)


def test_restitution_scales_the_exchange():
    e = 0.95
    vel, _ = collide((0, 0), (2 * R, 0), (2.0, 0), (0, 0), PhysicsParams(e_ball=e).array())
    assert vel[0, 0] == pytest.approx(2.0 * (1 - e) / 2)
    assert vel[1, 0] == pytest.approx(2.0 * (1 + e) / 2)


def test_separating_balls_do_not_collide():
    vel, speed = collide((0, 0), (2 * R, 0), (-1.0, 0), (0, 0))
    assert speed == 0.0
    assert vel[0, 0] == -1.0


def brute_force_contact(d, v, reach, horizon, steps=200_000):
    ts = np.linspace(0, horizon, steps)
    dist = np.hypot(d[0] + v[0] * ts, d[1] + v[1] * ts)
    hit = np.flatnonzero(dist <= reach)
    return ts[hit[0]] if len(hit) else math.inf


coords = st.floats(-0.3, 0.3, allow_nan=False)
speeds = st.floats(-12, 12, allow_nan=False)


@settings(max_examples=60, deadline=None)
@given(dx=coords, dy=coords, vx=speeds, vy=speeds)
def test_time_of_impact_matches_a_fine_step_search(dx, dy, vx, vy):
    reach = 2 * R
    if math.hypot(dx, dy) <= reach:
        dx, dy = dx + 3 * reach, dy  # start apart
    horizon = 0.1
    t = quadratic_contact_time(dx, dy, vx, vy, reach)
    brute = brute_force_contact((dx, dy), (vx, vy), reach, horizon)
    step = horizon / 199_999
    speed = math.hypot(vx, vy)
    if brute == math.inf:
        # Nothing within the horizon (or a graze thinner than the search grid can see).
        assert t > horizon - step or abs(math.hypot(dx + vx * t, dy + vy * t) - reach) < 1e-9
    else:
        assert t == pytest.approx(brute, abs=step + 1e-9 / max(speed, 1e-9))
        assert math.hypot(dx + vx * t, dy + vy * t) == pytest.approx(reach, abs=1e-9)


def test_touching_and_approaching_collides_now_and_overlap_from_round_off_too():
    assert quadratic_contact_time(2 * R, 0.0, -1.0, 0.0, 2 * R) == 0.0
    assert quadratic_contact_time(2 * R - 1e-12, 0.0, -1.0, 0.0, 2 * R) == 0.0
    # touching but separating: no event
    assert quadratic_contact_time(2 * R - 1e-12, 0.0, 1.0, 0.0, 2 * R) == math.inf


def test_line_contact_time_is_linear():
    # centre 0.1 m above a line y=0, moving down at 2 m/s: touches (R away) at (0.1 - R)/2.
    t = line_contact_time(0.5, 0.1, 0.0, -2.0, 0.0, 0.0, 0.0, 1.0, R)
    assert t == pytest.approx((0.1 - R) / 2)
    assert line_contact_time(0.5, 0.1, 0.0, 2.0, 0.0, 0.0, 0.0, 1.0, R) == math.inf
