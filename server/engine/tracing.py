"""A shot's exact motion as per-ball knots (`ShotInMotion.run(trace=...)`), for clients that
draw it: straight lines between the knots pass within a tolerance of where the engine has
each ball at every tick's end and every event, and a ball's own contacts are knots.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Tolerance:
    """How far the straight lines between a trace's knots may stray from the engine's
    balls: `position` in m, `phase` in radians of roll."""

    position: float
    phase: float


@dataclass(frozen=True)
class Trace:
    """A traced shot: its samples (t = 0, every event time, every tick's end) and, per
    ball, the samples kept as knots.

    Rows follow `ids` (as `ShotResult.ids`). Ball row b's knots are the sample indices
    `knots[offsets[b]:offsets[b + 1]]` (`knots_of(b)`): none for a ball off the table from
    the start, else the first sample, a knot at each of the ball's events, and up to its
    pocket or to where it last moved. Two kinds of event get no sample of their own: those
    of a tick with more distinct event times than the tracer replays (24, pockets always
    are; a rack's cascade has fewer), and those within 1e-9 s of their tick's start (the
    start stands for them)."""

    ids: np.ndarray  # (N,)
    times: np.ndarray  # (S,) s
    positions: np.ndarray  # (S, N, 2) m
    phases: np.ndarray  # (S, N) rad rolled
    on_table: np.ndarray  # (S, N) bool
    knots: np.ndarray  # (K,) sample indices, ball by ball
    offsets: np.ndarray  # (N + 1,)
    pockets: np.ndarray  # (N,) the pocket each ball dropped in, -1, or OFF_TABLE (-2)
    ticks: int  # as many as the shot's frames
    # (S, N) m: a flying ball's height above its resting height, 0 on the bed (the knots'
    # straight lines pass within the position tolerance of it too).
    heights: np.ndarray | None = None

    @property
    def flies(self) -> bool:
        """Some ball leaves the bed in this shot."""
        return self.heights is not None and bool(self.heights.any())

    def knots_of(self, row: int) -> np.ndarray:
        """The sample indices of ball row `row`'s knots."""
        return self.knots[self.offsets[row] : self.offsets[row + 1]]
