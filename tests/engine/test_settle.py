"""`settle`, the search's door: one compiled call from strike to final table, its events
kept as the kernel's rows until asked for. It must be `simulate` without the frames."""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from server.engine import CUE, Shot, Table, rack, settle, simulate
from server.engine.physics.borrow import borrowed

TABLE = Table.pool("9ft")
ARRAYS = ("ids", "positions", "velocities", "spins", "states", "phases", "pockets")


def _shots() -> list[Shot]:
    balls = rack("eight_ball", TABLE, seed=7)
    cx, cy = balls.position_of(CUE)
    fx, fy = TABLE.foot_spot
    aim = math.atan2(fy - cy, fx - cx)
    return [Shot(aim, 10.0), Shot(aim + 0.3, 2.0, (0.2, -0.3)), Shot(aim - 1.2, 0.6, (0.0, 0.4))]


def test_settle_is_simulate_without_frames_and_leaves_its_input_alone() -> None:
    balls = rack("eight_ball", TABLE, seed=7)
    before = {name: getattr(balls, name).copy() for name in ARRAYS}
    for shot in _shots():
        settled, simulated = settle(TABLE, balls, shot), simulate(TABLE, balls, shot)
        assert settled.events == simulated.events
        assert settled.duration == simulated.duration
        for name in ARRAYS:
            assert np.array_equal(getattr(settled.final, name), getattr(simulated.final, name))
            assert np.array_equal(getattr(balls, name), before[name])  # untouched
        assert not np.shares_memory(settled.final.positions, balls.positions)


def test_a_thousand_settles_of_one_table_stay_the_same() -> None:
    """The tick loop hands ownerless views of the caller's arrays to its helpers
    (`physics.borrow`): were an owner's count wrong, the arrays would be freed under the
    caller and later shots would read garbage."""
    balls = rack("eight_ball", TABLE, seed=7)
    shot = _shots()[1]
    first = settle(TABLE, balls, shot)
    for _ in range(1000):
        again = settle(TABLE, balls, shot)
    assert again.events == first.events
    assert np.array_equal(again.final.positions, first.final.positions)


@njit(cache=True)
def _double_through_view(values: np.ndarray) -> float:
    view = borrowed(values)
    for i in range(view.shape[0]):
        view[i] *= 2.0
    return view.sum()


def test_a_borrowed_view_is_the_array_itself() -> None:
    values = np.arange(5.0)
    assert _double_through_view(values) == 20.0
    assert values.tolist() == [0.0, 2.0, 4.0, 6.0, 8.0]
