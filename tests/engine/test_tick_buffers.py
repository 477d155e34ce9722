"""The compiled shot loop grows its event and frame arrays mid-shot (`run_ticks` stops
before a tick that might not fit, `run_to_rest_kernel` doubles the arrays and goes on):
a shot that has to grow them must come out as one that never does, bit for bit."""

from __future__ import annotations

import math

import numpy as np

from server.engine import CUE, DEFAULT_TICK, Shot, Table, rack
from server.engine.params import DEFAULT_PARAMS
from server.engine.simulate import _geometry, _run_kernel, strike


def _break(event_capacity: int) -> tuple:
    """A 12 m/s 8-ball break run by the kernel with frames, its event array starting at
    `event_capacity` rows (the kernel keeps at least MAX_EVENTS_PER_TICK + 128)."""
    table = Table.pool("9ft")
    balls = rack("eight_ball", table, seed=4)
    cx, cy = balls.position_of(CUE)
    fx, fy = table.foot_spot
    strike(balls, Shot(math.atan2(fy - cy, fx - cx), 12.0), DEFAULT_PARAMS)
    out = _run_kernel(_geometry(table), balls, DEFAULT_TICK, DEFAULT_PARAMS.array(), event_capacity)
    return (*out, balls)


def test_a_break_that_grows_its_arrays_is_the_same_break() -> None:
    grown = _break(0)  # room for 64 events before the first growth: a break logs more
    roomy = _break(1 << 16)
    _positions, _cels, _on_table, events, stalls, ticks, final = grown
    # The kernel grows the event array before a tick once fewer than
    # MAX_EVENTS_PER_TICK + 65 rows are free: here after the 64th event, and events
    # come a tick or more later, so they were written into the grown array.
    assert events[-1, 0] - events[63, 0] > DEFAULT_TICK
    assert ticks > 256  # the frame arrays grew too (256 rows at first)
    for a, b in zip(grown[:4], roomy[:4], strict=True):
        assert a.shape == b.shape
        assert a.tobytes() == b.tobytes()
    assert (stalls, ticks) == roomy[4:6]
    for name in ("positions", "velocities", "spins", "states", "phases", "pockets"):
        assert np.array_equal(getattr(final, name), getattr(roomy[6], name))
