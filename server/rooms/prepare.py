"""Simulate a shot and encode what the room will stream (pure: runs in a worker process
or thread, see `ShotRunner`)."""

from __future__ import annotations

from server.engine import BallSet, Shot, ShotResult, Table, rack, simulate
from server.protocol.plan import ShotPlan, plan_shot


def prepare_shot(
    table: Table,
    before: BallSet,
    shot: Shot,
    shot_id: int,
    frame_every: int,
    frames_per_message: int,
) -> tuple[ShotResult, ShotPlan]:
    """Simulate and plan a shot and encode its messages (runs in a worker thread)."""
    result = simulate(table, before, shot)
    return result, plan_shot(result, shot_id, frame_every, frames_per_message)


def warm_up(frame_every: int = 6) -> None:
    """Load the compiled engine and frame encoder (numba's cache; compiled on a fresh
    clone) before the first player shoots: the first call takes ~0.4 s, and holds the GIL
    the event loop needs, so doing it at a shot would stall every room's stream."""
    table = Table.pool("9ft")
    balls = rack("eight_ball", table, seed=0)
    prepare_shot(table, balls, Shot(0.0, 9.0), 0, frame_every, 2)
