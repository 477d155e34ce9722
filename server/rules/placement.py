"""Where the cue ball may go with ball in hand."""

from __future__ import annotations

import math

import numpy as np

from server.engine import CUE, BallSet, Table

from .outcome import BEHIND_HEAD_STRING, IN_D


def is_free(table: Table, balls: BallSet, x: float, y: float, ignore: int = CUE) -> bool:
    """A ball centred at (x, y) overlaps no ball on the table (other than `ignore`)."""
    on = balls.on_table & (balls.ids != ignore)
    if not on.any():
        return True
    d2 = np.sum((balls.positions[on] - (x, y)) ** 2, axis=1)
    return bool(np.all(d2 >= (2 * table.ball_radius) ** 2))


def can_place(table: Table, balls: BallSet, area: str | None, x: float, y: float) -> bool:
    """The cue ball may be put at (x, y) with ball in hand `area`.

    Inside the bed clear of the cushions, not overlapping another ball and, for
    "behind_head_string", with its centre on or behind the head string (x <= head_string);
    for "in_d", in the D (snooker).
    """
    if area is None:
        return False
    if not (isinstance(x, (int, float)) and isinstance(y, (int, float))):
        return False
    if not (math.isfinite(x) and math.isfinite(y)):
        return False
    if not table.contains(x, y):
        return False
    if area == BEHIND_HEAD_STRING and x > table.head_string:
        return False
    if area == IN_D and not table.in_d(x, y):
        return False
    return is_free(table, balls, x, y)
