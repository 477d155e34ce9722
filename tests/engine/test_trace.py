"""The traced run (`ShotInMotion.run(trace=...)`, `simulate_traced`): the same compiled call
as the simulation, so the engine's result is `simulate`'s bit for bit; its tick ends are the
engine's frames, and every ball's own contacts are knots of its track."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from server.engine import (
    Shot,
    ShotInMotion,
    Table,
    Tolerance,
    Trace,
    rack,
    simulate,
    simulate_traced,
)
from tests.support.games import BREAK, EIGHT_BALL
from tests.support.results import assert_same_result

TABLE = Table.pool("9ft")
TOLERANCE = Tolerance(0.0002, 0.03)
STALLING = (28, Shot(-1.008541877928577, 4.930159020213607))  # a cluster stalls a tick
CONTACTS = ("ball", "cushion", "jaw", "pocket")


def traced(seed: int, shot: Shot):
    balls = rack("eight_ball", TABLE, seed=seed)
    return simulate(TABLE, balls, shot), *simulate_traced(TABLE, balls, shot, TOLERANCE)


def test_the_tracer_follows_the_engine_tick_for_tick():
    result, _, trace = traced(EIGHT_BALL, BREAK)
    assert trace.ticks == len(result.frames)
    ends = np.searchsorted(trace.times, (np.arange(len(result.frames)) + 1) / 120 - 1e-12)
    assert np.array_equal(trace.positions[ends], result.frames.positions)
    assert np.array_equal(trace.on_table[ends], result.frames.on_table)


@pytest.mark.parametrize(("seed", "shot"), [(EIGHT_BALL, BREAK), STALLING, (3, Shot(2.0, 6.0))])
def test_one_pass_gives_the_engines_result_bit_for_bit(seed, shot):
    """The traced run runs the ticks once for the engine and the trace: its result is
    `simulate`'s exactly (frames, events, the table at rest, stalled ticks)."""
    expected, got, _ = traced(seed, shot)
    assert_same_result(got, expected)


def test_a_shot_in_motion_gives_its_trace_once_run_with_a_tolerance():
    balls = rack("eight_ball", TABLE, seed=EIGHT_BALL)
    plain = ShotInMotion(TABLE, balls, BREAK)
    plain.run()
    with pytest.raises(RuntimeError):
        _ = plain.trace
    motion = ShotInMotion(TABLE, balls, BREAK)
    motion.run(trace=TOLERANCE)
    assert isinstance(motion.trace, Trace)
    assert motion.result().events == plain.result().events
    assert np.array_equal(motion.trace.ids, balls.ids)
    assert np.array_equal(motion.trace.pockets, motion.result().final.pockets)


def test_a_stalling_cluster_is_traced_too():
    """The tracer's per-tick buffers hold a tick that stalls (5,000 contacts, plus rests):
    they once overflowed and corrupted the heap."""
    result, _, trace = traced(*STALLING)
    assert result.stalled_ticks > 0
    assert trace.ticks == len(result.frames)


@pytest.mark.parametrize(
    ("seed", "shot"), [(EIGHT_BALL, BREAK), (3, Shot(2.0, 6.0)), (7, Shot(0.05, 7.0, (0.2, -0.3)))]
)
def test_every_contact_is_a_knot_of_each_of_its_balls(seed, shot):
    """At each contact's time every ball in it has a knot (within 1e-10 s: a ball at rest
    keeps its knot at the last sample where it had not moved yet). Left out, as the tracer
    leaves them: a tick with more distinct event times than it replays (24, a rack's
    cascade), and a contact within 1e-9 s of its tick's start (drawn at the start)."""
    result, _, trace = traced(seed, shot)
    tick = result.frames.tick
    times_in_tick: dict[int, set[float]] = {}
    for event in result.events[1:]:
        times_in_tick.setdefault(math.floor(event.time / tick), set()).add(event.time)
    row = {int(ball): i for i, ball in enumerate(trace.ids)}
    checked = 0
    for event in result.events:
        index = math.floor(event.time / tick)
        if (
            event.kind not in CONTACTS
            or len(times_in_tick[index]) > 24
            or event.time - index * tick <= 1e-9
        ):
            continue
        for ball in event.ids:
            knots = trace.times[trace.knots_of(row[ball])]
            assert np.abs(knots - event.time).min() < 1e-10, (event, ball)
            checked += 1
    assert checked >= 5


def test_knots_stay_within_the_tolerance_of_every_sample():
    _, _, trace = traced(EIGHT_BALL, BREAK)
    for b in range(len(trace.ids)):
        knots = trace.knots_of(b)
        for a, j in itertools.pairwise(knots):
            span = trace.times[j] - trace.times[a]
            for i in range(a + 1, j):
                f = (trace.times[i] - trace.times[a]) / span if span > 0 else 0.0
                line = trace.positions[a, b] + (trace.positions[j, b] - trace.positions[a, b]) * f
                assert np.hypot(*(line - trace.positions[i, b])) <= TOLERANCE.position
