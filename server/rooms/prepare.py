"""Simulate a shot and encode what the room will stream (pure: runs in a worker process
or thread, see `ShotRunner`)."""

from __future__ import annotations

from server.engine import BallSet, Shot, ShotInMotion, ShotResult, Table, rack
from server.protocol.motion import run_traced
from server.protocol.plan import ShotPlan, plan_shot


def prepare_shot(
    table: Table,
    before: BallSet,
    shot: Shot,
    shot_id: int,
    frame_every: int,
) -> tuple[ShotResult, ShotPlan]:
    """Simulate, trace and plan a shot and encode its `motion` message (a worker)."""
    motion = ShotInMotion(table, before, shot)
    tracks = run_traced(motion)  # the engine's ticks and the tracks, in one pass
    result = motion.result()
    return result, plan_shot(result, tracks, shot_id, frame_every)


def warm_up(frame_every: int = 6) -> None:
    """Load the compiled engine and motion tracer (numba's cache; compiled on a fresh
    clone) before the first player shoots: the first call takes ~0.4 s, and holds the GIL
    the event loop needs, so doing it at a shot would stall every room's stream."""
    table = Table.pool("9ft")
    balls = rack("eight_ball", table, seed=0)
    prepare_shot(table, balls, Shot(0.0, 9.0), 0, frame_every)
