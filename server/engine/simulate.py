"""The engine's two doors: `simulate` runs a whole shot to rest, `step` advances a live table
by one tick. Both trust their input (the room validates a player's shot first) and are
deterministic: the same table, balls and shot give the same result, bit for bit.
`ShotInMotion.run(trace=...)` (and `simulate_traced`) also trace the shot for drawing, in
the same compiled call.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .balls import CUE, BallSet
from .params import DEFAULT_PARAMS, PhysicsParams, params_for
from .physics.constants import POCKETED
from .physics.motion import drop_residual_spin, strike_ball
from .physics.tick import empty_events, run_tick, run_to_rest_kernel, settle_kernel
from .physics.trace import traced_run_kernel
from .results import Event, EventKind, FrameSequence, Settled, ShotResult, events_from
from .shot import Shot
from .table import Table
from .tracing import Tolerance, Trace

TICK_HZ = 120  # ticks per second: fixed, so clients are told it rather than a setting
DEFAULT_TICK = 1.0 / TICK_HZ
MAX_SHOT_SECONDS = 300.0  # no real shot comes close; a guard, not a rule
_EVENT_CAPACITY = 16384


class _Geometry:
    """The table as the arrays the kernels take, built once per Table."""

    __slots__ = ("centers", "cushions", "jaws", "length", "pockets", "width")

    def __init__(self, table: Table) -> None:
        self.cushions = table.cushion_array()
        self.jaws = table.jaw_array()
        self.pockets = table.pocket_array()
        self.centers = table.pocket_centers()
        self.length = float(table.length)
        self.width = float(table.width)


_geometry_cache: dict[Table, _Geometry] = {}
_last_geometry: tuple[Table, _Geometry] | None = None  # the search asks for one table


def _geometry(table: Table) -> _Geometry:
    """The arrays of `table`. The table last asked for is found by identity: hashing a
    Table (every cushion and pocket) cost more than a short shot's Python around it."""
    global _last_geometry
    last = _last_geometry
    if last is not None and last[0] is table:
        return last[1]
    geo = _geometry_cache.get(table)
    if geo is None:
        geo = _geometry_cache[table] = _Geometry(table)
    _last_geometry = (table, geo)
    return geo


_last_params: tuple[PhysicsParams, np.ndarray] | None = None


def _params_array(params: PhysicsParams) -> np.ndarray:
    """`params.array()`, kept for the parameters last asked for (found by identity, as the
    table is): building it cost as much as a short shot's strike. The kernels only read it."""
    global _last_params
    last = _last_params
    if last is not None and last[0] is params:
        return last[1]
    values = params.array()
    _last_params = (params, values)
    return values


def _cue_row(balls: BallSet, ball: int = CUE) -> int:
    """The struck ball's row; ValueError when it is not on the table."""
    try:
        row = balls.index(ball)
    except KeyError:
        raise ValueError(f"ball {ball} is not in the set") from None
    if balls.states[row] == POCKETED:
        raise ValueError("the cue ball is not on the table")
    return row


def strike(
    balls: BallSet, shot: Shot, params: PhysicsParams = DEFAULT_PARAMS, time: float = 0.0
) -> Event:
    """Give the struck ball (`shot.ball`, the cue ball) the shot's velocity and spin (in
    place); returns the strike event."""
    row = _cue_row(balls, shot.ball)
    (vx, vy), (wx, wy, wz) = shot.cue_ball_motion(params.radius, params.cue_mass_ratio)
    strike_ball(
        balls.velocities, balls.spins, balls.states, balls.heights, row, vx, vy, wx, wy, wz,
        shot.downward_speed(), _params_array(params),
    )  # fmt: skip
    return Event(time, _STRIKE, (shot.ball,), float(shot.speed))


_STRIKE = EventKind.STRIKE.value


def step(
    table: Table,
    balls: BallSet,
    tick: float = DEFAULT_TICK,
    time: float = 0.0,
    params: PhysicsParams | None = None,
) -> list[Event]:
    """Advance `balls` in place by one tick; returns the tick's events (times from `time`).
    `params` default to the table's (`params_for`), as in every door below."""
    geo = _geometry(table)
    params = params if params is not None else params_for(table)
    events = empty_events(_EVENT_CAPACITY)
    n_ev, _ = run_tick(
        balls.positions,
        balls.velocities,
        balls.spins,
        balls.states,
        balls.phases,
        balls.pockets,
        balls.heights,
        geo.cushions,
        geo.jaws,
        geo.pockets,
        geo.centers,
        geo.length,
        geo.width,
        _params_array(params),
        float(tick),
        float(time),
        events,
        0,
    )
    return events_from(events[:n_ev], balls.ids)


def _run_kernel(
    geo: _Geometry,
    s: BallSet,
    tick: float,
    params: np.ndarray,
    event_capacity: int = _EVENT_CAPACITY,
) -> tuple[Any, ...]:
    """(frame positions, cels, on-table flags, event rows, stalled ticks, ticks); `s` is
    advanced in place to rest. The event array starts at `event_capacity` rows and grows
    as needed. (`settle_kernel` runs a shot without frames.)"""
    raw: tuple[Any, ...] = run_to_rest_kernel(
        s.positions,
        s.velocities,
        s.spins,
        s.states,
        s.phases,
        s.pockets,
        s.heights,
        geo.cushions,
        geo.jaws,
        geo.pockets,
        geo.centers,
        geo.length,
        geo.width,
        params,
        tick,
        int(MAX_SHOT_SECONDS / tick),
        event_capacity,
        True,
    )
    return raw


class ShotInMotion:
    """A shot in three parts, so a server can run the long middle one in a thread without
    holding the GIL its event loop needs: the strike (here), `run()` (the whole tick loop,
    one compiled call that releases the GIL) and `result()` (Python objects again).

    `simulate` is the three in a row; splitting them changes nothing in the result.
    `run(trace=tolerance)` also traces the shot (`trace`) in the same compiled call: the
    same ticks, so `result()` is the same, bit for bit."""

    def __init__(
        self,
        table: Table,
        balls: BallSet,
        shot: Shot,
        tick: float = DEFAULT_TICK,
        params: PhysicsParams | None = None,
    ) -> None:
        params = params if params is not None else params_for(table)
        self.tick = float(tick)
        self.state = balls.copy()
        self._events = [strike(self.state, shot, params)]
        self._geometry = _geometry(table)
        self._params = _params_array(params)
        self._raw: tuple[Any, ...] | None = None
        self._trace: Trace | None = None

    def run(self, trace: Tolerance | None = None) -> None:
        """Run every tick until the balls are at rest (the guard: MAX_SHOT_SECONDS); with a
        `trace` tolerance, trace the shot too (`self.trace`)."""
        if trace is None:
            self._raw = _run_kernel(self._geometry, self.state, self.tick, self._params)
            return
        s, geo = self.state, self._geometry
        ids = s.ids.copy()
        traced = traced_run_kernel(
            s.positions, s.velocities, s.spins, s.states, s.phases, s.pockets, s.heights,
            geo.cushions, geo.jaws, geo.pockets, geo.centers, geo.length, geo.width,
            self._params, self.tick, int(MAX_SHOT_SECONDS / self.tick), float(trace.position),
            float(trace.phase),
        )  # fmt: skip
        times, positions, phases, on_table, knots, offsets, heights, ticks, self._raw = traced
        self._trace = Trace(
            ids, times, positions, phases, on_table, knots, offsets, s.pockets.copy(), ticks,
            heights,
        )  # fmt: skip

    @property
    def trace(self) -> Trace:
        """The shot's tracks (after `run(trace=...)`)."""
        if self._trace is None:
            raise RuntimeError("run(trace=...) the shot first")
        return self._trace

    def result(self) -> ShotResult:
        if self._raw is None:
            raise RuntimeError("run() the shot first")
        positions, cels, on_table, rows, stalls, _ = self._raw
        state = self.state
        events = self._events + events_from(rows, state.ids)
        drop_residual_spin(state.spins, state.states)
        frames = FrameSequence(self.tick, positions, cels, on_table)
        return ShotResult(state.ids.copy(), frames, events, state, int(stalls))


def simulate(
    table: Table,
    balls: BallSet,
    shot: Shot,
    tick: float = DEFAULT_TICK,
    params: PhysicsParams | None = None,
) -> ShotResult:
    """Strike the cue ball and run ticks until every ball is at rest or pocketed.

    `balls` is not modified. Residual spin about the vertical axis of a ball that has
    stopped translating is dropped at the end (it cannot move the ball any more).
    """
    motion = ShotInMotion(table, balls, shot, tick, params)
    motion.run()
    return motion.result()


def simulate_traced(
    table: Table,
    balls: BallSet,
    shot: Shot,
    tolerance: Tolerance,
    tick: float = DEFAULT_TICK,
    params: PhysicsParams | None = None,
) -> tuple[ShotResult, Trace]:
    """`simulate` and the shot's trace (within `tolerance`) from one pass over its ticks:
    the result is `simulate`'s, bit for bit. `balls` is not modified."""
    motion = ShotInMotion(table, balls, shot, tick, params)
    motion.run(trace=tolerance)
    return motion.result(), motion.trace


def settle(
    table: Table,
    balls: BallSet,
    shot: Shot,
    tick: float = DEFAULT_TICK,
    params: PhysicsParams | None = None,
) -> Settled:
    """`simulate` without the frames: the same events, final table and duration, bit for
    bit, in about two fifths of the time for the short shots a search tries (less is saved
    on a break, whose many events cost the same either way). `balls` is not modified."""
    params = params if params is not None else params_for(table)
    row = _cue_row(balls, shot.ball)
    (vx, vy), (wx, wy, wz) = shot.cue_ball_motion(params.radius, params.cue_mass_ratio)
    geo, dt = _geometry(table), float(tick)
    *arrays, rows, stalls, ticks = settle_kernel(
        balls.positions, balls.velocities, balls.spins, balls.states, balls.phases,
        balls.pockets, balls.heights, row, vx, vy, wx, wy, wz, shot.downward_speed(),
        geo.cushions, geo.jaws, geo.pockets, geo.centers, geo.length, geo.width,
        _params_array(params), dt, int(MAX_SHOT_SECONDS / dt), _EVENT_CAPACITY,
    )  # fmt: skip
    final = BallSet.of_arrays(balls.ids.copy(), *arrays)
    return Settled(rows, final, ticks * dt, int(stalls), float(shot.speed), shot.ball)


def run_to_rest(
    table: Table,
    state: BallSet,
    tick: float = DEFAULT_TICK,
    params: PhysicsParams | None = None,
    events: list[Event] | None = None,
) -> FrameSequence:
    """Advance `state` in place until no ball moves; appends events to `events`."""
    params = params if params is not None else params_for(table)
    positions, cels, on_table, rows, _, _ = _run_kernel(
        _geometry(table), state, float(tick), _params_array(params)
    )
    if events is not None:
        events.extend(events_from(rows, state.ids))
    return FrameSequence(float(tick), positions, cels, on_table)
