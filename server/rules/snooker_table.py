"""Snooker's geometry for the referee: whether the cue ball is snookered, and where a
colour goes back on the table.

WPBSA Section 2, 14 Snookered: "The cue-ball is snookered when a direct stroke in a
straight line to every ball on is wholly or partially obstructed by a ball or balls not
on. If one or more balls on can be struck at both extreme edges free of obstruction, the
cue-ball is not snookered." Cushions are not obstructions here (the WPBSA's "angled"
cue ball, Section 2, 15, behind a pocket's jaw, is not judged).

WPBSA Section 3, 6 Spotting Colours: a colour goes on its own spot; if that is occupied,
on the highest-valued spot available; if every spot is occupied, as near its own spot as
possible between it and the nearest part of the top cushion (along the long middle line);
and, for the pink and black when that line is full, as near as possible below its spot.
"Occupied": a ball placed there would touch another ball.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence

import numpy as np

from server.engine import CUE, BallSet, Table

from .snooker_score import COLOUR_IDS, NAMES, VALUES

SPOT_GAP = 1e-5  # m between a spotted ball and one it would otherwise touch
LINE_STEP = 1e-3  # m between the points tried along the long middle line


def _corridor_clear(start: np.ndarray, end: np.ndarray, others: np.ndarray, reach: float) -> bool:
    """No centre in `others` lies within `reach` of the segment start-end."""
    if len(others) == 0:
        return True
    d = end - start
    length2 = float(d @ d) or 1e-18
    t = np.clip(((others - start) @ d) / length2, 0.0, 1.0)
    nearest = start + t[:, None] * d
    return bool(np.all(np.sum((others - nearest) ** 2, axis=1) >= reach * reach))


def edges_clear(table: Table, balls: BallSet, target: int, on: Iterable[int]) -> bool:
    """The cue ball can strike `target` at both extreme edges free of obstruction by a
    ball not on: the cue ball's path to each grazing contact (its centre passing 2R from
    the target's, either side) meets no ball not on."""
    r = table.ball_radius
    cue = np.array(balls.position_of(CUE))
    aim = np.array(balls.position_of(target))
    gap = aim - cue
    dist = float(np.hypot(*gap))
    if dist < 1e-12:
        return True
    across = np.array([-gap[1], gap[0]]) / dist
    allowed = {CUE, target, *on}
    rows = [i for i, b in enumerate(balls.ids.tolist()) if b not in allowed and balls.on_table[i]]
    others = balls.positions[rows]
    return all(
        _corridor_clear(cue, aim + side * 2 * r * across, others, 2 * r - 1e-9) for side in (+1, -1)
    )


def snookered(table: Table, balls: BallSet, on: Sequence[int]) -> bool:
    """WPBSA Section 2, 14: no ball on can be struck at both extreme edges.

    `edges_clear` for every ball on at once (one array computation: the search judges
    thousands of simulated fouls a turn, each asking this)."""
    here = set(balls.on_table_ids())
    present = [b for b in on if b in here]
    if not present or CUE not in here:
        return False
    rows = np.array([balls.index(b) for b in present])
    positions = balls.positions
    cue = positions[balls.index(CUE)]
    aims = positions[rows]
    gap = aims - cue
    dist = np.hypot(gap[:, 0], gap[:, 1])
    if np.any(dist < 1e-12):
        return False
    others = positions[balls.on_table & ~np.isin(balls.ids, [CUE, *present])]
    if len(others) == 0:
        return False
    r = table.ball_radius
    across = np.stack([-gap[:, 1], gap[:, 0]], axis=1) / dist[:, None]
    ends = np.concatenate([aims + 2 * r * across, aims - 2 * r * across]) - cue
    length2 = np.sum(ends * ends, axis=1)
    length2[length2 == 0.0] = 1e-18
    t = np.clip(((others - cue) @ ends.T) / length2, 0.0, 1.0)
    nearest = cue + t[:, :, None] * ends[None, :, :]
    reach = 2 * r - 1e-9
    clear = np.all(np.sum((others[:, None, :] - nearest) ** 2, axis=2) >= reach * reach, axis=0)
    k = len(present)
    return not bool(np.any(clear[:k] & clear[k:]))


def _free(table: Table, balls: BallSet, ball: int, xy: tuple[float, float]) -> bool:
    x, y = xy
    if not table.contains(x, y):
        return False
    reach = 2 * table.ball_radius + SPOT_GAP
    on = balls.on_table & (balls.ids != ball)
    d2 = np.sum((balls.positions[on] - (x, y)) ** 2, axis=1)
    return bool(np.all(d2 >= reach * reach))


def spot_point(table: Table, balls: BallSet, ball: int) -> tuple[float, float]:
    """Where colour `ball` is re-spotted (WPBSA Section 3, 6)."""
    spots = table.spots
    own = spots[NAMES[ball]]
    if _free(table, balls, ball, own):
        return own
    for colour in sorted(COLOUR_IDS, key=VALUES.__getitem__, reverse=True):
        if _free(table, balls, ball, spots[NAMES[colour]]):
            return spots[NAMES[colour]]
    x0, y0 = own
    top = table.length - table.ball_radius
    steps = math.ceil((top - x0) / LINE_STEP)
    for k in range(1, steps + 1):
        xy = (min(x0 + k * LINE_STEP, top), y0)
        if _free(table, balls, ball, xy):
            return xy
    for k in range(1, int(x0 / LINE_STEP)):
        xy = (x0 - k * LINE_STEP, y0)
        if _free(table, balls, ball, xy):
            return xy
    raise ValueError("no free point on the long middle line")  # needs more balls than exist


def respot_colours(table: Table, balls: BallSet, ball_ids: Iterable[int]) -> BallSet:
    """A copy of `balls` with each colour of `ball_ids` spotted, the highest value first
    (it has precedence when spots are occupied)."""
    out = balls
    for ball in sorted(ball_ids, key=VALUES.__getitem__, reverse=True):
        out = out.with_ball(ball, spot_point(table, out, ball))
    return out
