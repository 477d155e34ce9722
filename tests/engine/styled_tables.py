"""Property-test pieces shared by the tables of other styles (snooker, carom): random
placements on a table and the energy check of a shot played tick by tick."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import assume
from hypothesis import strategies as st

from server.engine import BallSet, Shot, Table, step, strike
from server.engine.params import params_for

from .conftest import in_play_area

TICK = 1 / 120

SHOTS = st.builds(
    Shot,
    angle=st.floats(-math.pi, math.pi, allow_nan=False),
    speed=st.floats(0.05, 8.0, allow_nan=False),
    tip=st.tuples(st.floats(-0.35, 0.35), st.floats(-0.35, 0.35)),
)


@st.composite
def placements(draw: st.DrawFn, table: Table, balls: st.SearchStrategy[int]) -> BallSet:
    """`balls` balls at random points of `table`'s playing area, none overlapping."""
    r = table.ball_radius
    xs = st.floats(r, table.length - r, allow_nan=False)
    ys = st.floats(r, table.width - r, allow_nan=False)
    spots: list[tuple[float, float]] = []
    for _ in range(draw(balls)):
        x, y = draw(xs), draw(ys)
        assume(all(math.hypot(x - a, y - b) >= 2 * r for a, b in spots))
        assume(in_play_area(table, np.array([x, y]))[0])
        spots.append((x, y))
    return BallSet.place(dict(enumerate(spots)))


def assert_energy_never_rises(table: Table, balls: BallSet, shot: Shot, ticks: int) -> None:
    """Play `shot` tick by tick: the kinetic energy never rises and the balls come to rest
    within `ticks`."""
    params = params_for(table)
    strike(balls, shot, params)
    energy = balls.kinetic_energy(params.mass, table.ball_radius)
    for k in range(ticks):
        step(table, balls, TICK, k * TICK)
        now = balls.kinetic_energy(params.mass, table.ball_radius)
        assert now <= energy * (1 + 1e-12) + 1e-15
        energy = now
        if balls.at_rest():
            break
    assert balls.at_rest()
