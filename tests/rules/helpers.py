"""Shared builders for the rules tests: crafted shot results and real straight-in shots."""

from __future__ import annotations

import math

import numpy as np

from server.engine import (
    OFF_TABLE,
    BallSet,
    Event,
    FrameSequence,
    MotionState,
    Shot,
    ShotResult,
    Table,
)
from server.rules import Game

TABLE = Table.pool("9ft")


def hit(a: int, b: int) -> Event:
    return Event(0.0, "ball", (a, b), 1.0)


def rail(ball: int, cushion: int = 0) -> Event:
    return Event(0.0, "cushion", (ball,), 1.0, cushion)


def pot(ball: int, pocket: int = 0) -> Event:
    return Event(0.0, "pocket", (ball,), 1.0, pocket)


def off(ball: int, cushion: int = 0) -> Event:
    """The ball flies over `cushion` and off the table (a jump gone wrong)."""
    return Event(0.0, "off_table", (ball,), 3.0, cushion)


def crafted(before: BallSet, *events: Event) -> ShotResult:
    """A ShotResult whose final table is `before` with the balls of the pocket events
    dropped and those of the off-table events out of play (pocket OFF_TABLE); event times
    increase in the order given."""
    timed = [Event(0.0, "strike", (0,), 2.0)]
    timed += [Event(0.01 * (k + 1), e.kind, e.ids, e.speed, e.target) for k, e in enumerate(events)]
    final = before.copy()
    for e in events:
        if e.kind == "pocket":
            row = final.index(e.ids[0])
            final.states[row] = MotionState.POCKETED
            final.pockets[row] = e.target
            final.positions[row] = TABLE.pockets[e.target].center
        elif e.kind == "off_table":
            row = final.index(e.ids[0])
            final.states[row] = MotionState.POCKETED
            final.pockets[row] = OFF_TABLE
    n = len(before)
    frames = FrameSequence(
        1 / 120, np.empty((0, n, 2)), np.empty((0, n), dtype=np.int64), np.empty((0, n), dtype=bool)
    )
    return ShotResult(before.ids.copy(), frames, timed, final)


def park_slots() -> list[tuple[float, float]]:
    """Spots far from the bottom-left and top-left corners, for balls not in play."""
    return [(1.45 + 0.1 * i, 0.3 + 0.1 * j) for j in range(7) for i in range(8)]


def arrange(game: Game, placement: dict[int, tuple[float, float]]) -> None:
    """Set up a position: the balls in `placement` go there, other balls still on the
    table are parked; pocketed balls stay pocketed (ids are kept, as `apply` checks)."""
    balls = game.balls.copy()
    slots = iter(park_slots())
    for ball in [int(b) for b in balls.ids]:
        if ball in placement:
            balls = balls.with_ball(ball, placement[ball])
        elif balls.on_table[balls.index(ball)]:
            balls = balls.with_ball(ball, next(slots))
    game.balls = balls


def straight_in(
    ball: int, pocket: int = 0, dist: float = 0.25, gap: float = 0.2
) -> tuple[dict[int, tuple[float, float]], Shot]:
    """Object ball `dist` from the pocket mouth, cue ball `gap` behind it, a draw shot
    straight in (the cue ball comes back)."""
    p = TABLE.pockets[pocket]
    mx = (p.jaws[0][0] + p.jaws[1][0]) / 2
    my = (p.jaws[0][1] + p.jaws[1][1]) / 2
    ox, oy = p.outward
    target = (mx - ox * dist, my - oy * dist)
    cue = (target[0] - ox * gap, target[1] - oy * gap)
    return {ball: target, 0: cue}, Shot(math.atan2(oy, ox), 2.0, (0.0, -0.3))


def aim(src: tuple[float, float], dst: tuple[float, float]) -> float:
    return math.atan2(dst[1] - src[1], dst[0] - src[0])
