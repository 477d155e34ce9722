"""Properties that must hold for any table and any shot (hypothesis)."""

import hashlib
import math
import subprocess
import sys

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from server.engine import (
    BALL_MASS,
    BALL_RADIUS,
    DEFAULT_PARAMS,
    BallSet,
    MotionState,
    Shot,
    Table,
    simulate,
    step,
    strike,
)
from server.engine.physics.constants import EPS_SPEED
from server.engine.physics.resolve import ball_ball

from .conftest import in_play_area, pair_min_gap

TABLE = Table.pool("9ft")
R = BALL_RADIUS
TICK = 1 / 120


@st.composite
def placements(draw, min_balls=2, max_balls=16):
    """Non-overlapping stationary balls anywhere on the bed (ids 0..n-1)."""
    n = draw(st.integers(min_balls, max_balls))
    xs = st.floats(R, TABLE.length - R, allow_nan=False)
    ys = st.floats(R, TABLE.width - R, allow_nan=False)
    spots: list[tuple[float, float]] = []
    for _ in range(n):
        x, y = draw(xs), draw(ys)
        assume(all(math.hypot(x - a, y - b) >= 2 * R for a, b in spots))
        assume(in_play_area(TABLE, np.array([x, y]))[0])
        spots.append((x, y))
    return BallSet.place(dict(enumerate(spots)))


shots = st.builds(
    Shot,
    angle=st.floats(-math.pi, math.pi, allow_nan=False),
    speed=st.floats(0.05, 12.0, allow_nan=False),
    tip=st.tuples(st.floats(-0.35, 0.35), st.floats(-0.35, 0.35)),
)

SETTINGS = settings(
    max_examples=40,
    deadline=None,
    suppress_health_check=[HealthCheck.filter_too_much, HealthCheck.too_slow],
)


@pytest.mark.slow  # many seconds: not in scripts/test --quick
@SETTINGS
@given(balls=placements(), shot=shots)
def test_every_tick_ends_without_overlap_and_on_the_bed(balls, shot):
    result = simulate(TABLE, balls, shot)
    assert result.stalled_ticks == 0
    frames = result.frames
    for k in range(len(frames)):
        on = frames.on_table[k]
        assert pair_min_gap(frames.positions[k], on, R) >= -1e-9
        assert in_play_area(TABLE, frames.positions[k][on]).all()
    assert result.final.at_rest()
    # Pocketed balls are off the table for good.
    pocketed = set(result.pocketed())
    assert pocketed == set(result.final.pocketed_ids())
    assert len(pocketed) == len(result.pocketed())


@SETTINGS
@given(balls=placements(max_balls=8), shot=shots)
def test_kinetic_energy_never_increases(balls, shot):
    strike(balls, shot)
    energy = balls.kinetic_energy(BALL_MASS, BALL_RADIUS)
    for k in range(3000):
        step(TABLE, balls, TICK, k * TICK)
        now = balls.kinetic_energy(BALL_MASS, BALL_RADIUS)
        assert now <= energy * (1 + 1e-12) + 1e-15
        energy = now
        if balls.at_rest():
            break
    assert balls.at_rest()


vectors = st.tuples(st.floats(-12, 12), st.floats(-12, 12))


@settings(max_examples=200, deadline=None)
@given(angle=st.floats(-math.pi, math.pi), v1=vectors, v2=vectors, e=st.floats(0.5, 1.0))
def test_ball_ball_event_conserves_momentum_and_loses_energy(angle, v1, v2, e):
    pos = np.array([[0.0, 0.0], [2 * R * math.cos(angle), 2 * R * math.sin(angle)]])
    vel = np.array([v1, v2], dtype=float)
    before_p = vel.sum(axis=0)
    before_ke = float((vel**2).sum())
    w = np.zeros((2, 3))
    states = np.full(2, MotionState.SLIDING, dtype=np.int64)
    params = DEFAULT_PARAMS.__class__(e_ball=e).array()
    ball_ball(pos, vel, w, states, 0, 1, params)
    # exact, but for a ball left slower than EPS_SPEED, which the engine stops
    assert vel.sum(axis=0) == pytest.approx(before_p, abs=2 * EPS_SPEED)
    assert float((vel**2).sum()) <= before_ke * (1 + 1e-12) + 1e-15
    # afterwards they never approach (but for the speed of a ball the engine stopped)
    assert (vel[0] - vel[1]) @ (pos[0] - pos[1]) >= -2 * EPS_SPEED * 2 * R


@SETTINGS
@given(
    x=st.floats(0.2, 2.3),
    y=st.floats(0.2, 1.07),
    angle=st.floats(-math.pi, math.pi),
    distance=st.floats(2 * R + 1e-4, 1.0),
    speed=st.floats(6.0, 12.0),
)
def test_no_tunnelling_through_a_ball_at_full_speed(x, y, angle, distance, speed):
    d = np.array([math.cos(angle), math.sin(angle)])
    target = np.array([x, y]) + d * distance
    assume(TABLE.contains(*target) and TABLE.contains(x, y))
    result = simulate(TABLE, BallSet.place({0: (x, y), 1: tuple(target)}), Shot(angle, speed))
    first = result.events[1]
    assert (first.kind, set(first.ids)) == ("ball", {0, 1})


@SETTINGS
@given(x=st.floats(0.2, 2.3), y=st.floats(0.2, 1.07), angle=st.floats(-math.pi, math.pi))
def test_no_tunnelling_through_a_cushion_at_twelve_metres_per_second(x, y, angle):
    result = simulate(TABLE, BallSet.place({0: (x, y)}), Shot(angle, 12.0))
    first = result.events[1]
    assert first.kind in ("cushion", "jaw", "pocket")
    on = result.frames.on_table[:, 0]
    assert in_play_area(TABLE, result.frames.positions[on, 0]).all()


def digest(result) -> str:
    h = hashlib.sha256()
    for a in (
        result.frames.positions,
        result.frames.cels,
        result.frames.on_table,
        result.final.positions,
        result.final.phases,
    ):
        h.update(np.ascontiguousarray(a).tobytes())
    h.update(repr([(e.time, e.kind, e.ids, e.speed, e.target) for e in result.events]).encode())
    return h.hexdigest()


@SETTINGS
@given(balls=placements(max_balls=16), shot=shots)
def test_same_input_same_result_bit_for_bit(balls, shot):
    assert digest(simulate(TABLE, balls, shot)) == digest(simulate(TABLE, balls, shot))


def test_step_by_step_equals_simulate(table):
    from server.engine import rack

    balls = rack("eight_ball", table, seed=4)
    shot = Shot(0.02, 9.0, tip=(0.1, -0.2))
    whole = simulate(table, balls, shot)
    live = balls.copy()
    strike(live, shot)
    for k in range(len(whole.frames)):
        step(table, live, TICK, k * TICK)
        assert np.array_equal(live.positions, whole.frames.positions[k])
    assert live.at_rest()


def test_a_shot_run_in_threads_equals_simulate(table):
    """The server strikes on its loop, runs the tick loop in a thread (no GIL) and builds
    the result on the loop again: the same bits as `simulate`, even with shots running side
    by side."""
    from concurrent.futures import ThreadPoolExecutor

    from server.engine import ShotInMotion, rack

    cases = [
        (rack("eight_ball", table, seed=s), Shot(0.01 * s, 4.0 + s, tip=(0.0, 0.2)))
        for s in range(6)
    ]
    motions = [ShotInMotion(table, balls, shot) for balls, shot in cases]
    with pytest.raises(RuntimeError):
        motions[0].result()
    with ThreadPoolExecutor(3) as pool:
        list(pool.map(ShotInMotion.run, motions))
    for motion, (balls, shot) in zip(motions, cases, strict=True):
        assert digest(motion.result()) == digest(simulate(table, balls, shot))


SCRIPT = """
import hashlib, numpy as np
from server.engine import Table, Shot, rack, simulate
r = simulate(Table.pool("9ft"), rack("eight_ball", Table.pool("9ft"), seed=11), Shot(0.0, 10.0))
h = hashlib.sha256(r.frames.positions.tobytes() + r.final.positions.tobytes())
print(h.hexdigest())
"""


def test_another_process_gets_the_same_bits(table):
    from server.engine import rack

    r = simulate(table, rack("eight_ball", table, seed=11), Shot(0.0, 10.0))
    here = hashlib.sha256(r.frames.positions.tobytes() + r.final.positions.tobytes())
    out = subprocess.run(
        [sys.executable, "-c", SCRIPT], capture_output=True, text=True, check=True, timeout=240
    )
    assert out.stdout.strip() == here.hexdigest()


@SETTINGS
@given(balls=placements(max_balls=8), shot=shots)
def test_a_table_at_rest_shows_the_cels_of_the_last_frame(balls, shot):
    """A ball at rest shows the cel its roll gives (`BallSet.cels`): the live `state`, a
    re-spotted ball and a stored table all draw it from there, the stream from the frames."""
    result = simulate(TABLE, balls, shot)
    on = result.final.on_table
    assert np.array_equal(result.final.cels()[on], result.frames.cels[-1][on])
