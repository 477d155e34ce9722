"""Snooker's geometry for the referee: whether the cue ball is snookered, whether any
part of a ball on is open to a straight stroke, and where a colour goes back on the table.

WPBSA Section 2, Rule 17 Snookered: "The cue-ball is snookered when a direct stroke in a
straight line to every ball on is wholly or partially obstructed by a ball or balls not
on. If one or more balls on can be struck at both extreme edges free of obstruction, the
cue-ball is not snookered." The cue ball cannot be snookered by a cushion (2.17), so
cushions and jaws are no obstruction here. In hand, the cue ball is snookered only if it
would be from every point of the D (2.17); the referee here judges the cue ball where it
lies (`snooker._options` offers no free ball with the cue ball in hand).

WPBSA Section 3, Rule 14 Foul and a Miss calls a miss whenever there was "a clear path in
a straight line from the cue-ball to any part of any ball that is or could be on"
(`open_path`).

WPBSA Section 3, Rule 7 Spotting Colours: a colour goes on its own spot; if that is
occupied, on the highest-valued spot available; when more than one colour is to be
spotted and their own spots are occupied, the higher value is spotted first; if every
spot is occupied, as near its own spot as possible between it and the nearest part of the
top cushion (the line through its spot along the table); and, for the pink and black
when that line is full, as near as possible below its spot. Section 2, Rule 18 Spot
Occupied: a ball placed there would touch another ball.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence

import numpy as np

from server.engine import CUE, BallSet, Table

from .snooker_score import COLOUR_IDS, NAMES, VALUES

SPOT_GAP = 1e-5  # m between a spotted ball and one it would otherwise touch
LINE_STEP = 1e-3  # m between the points tried along the line through a spot
EDGES = np.array([1.0, -1.0])  # the two extreme edges, in units of 2R across the line
ANY_PART = np.linspace(-1.0, 1.0, 17)  # points across a ball on, edge to edge


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


def _present(balls: BallSet, on: Sequence[int]) -> list[int]:
    """The balls of `on` on the table, none when the cue ball is off it."""
    here = set(balls.on_table_ids())
    return [b for b in on if b in here] if CUE in here else []


def _clear_paths(
    table: Table, balls: BallSet, present: list[int], offsets: np.ndarray
) -> np.ndarray:
    """clear[i, j]: the cue ball's straight path to contact ball `present[j]` at
    `offsets[i]` (times 2R across the line of centres; +-1 the extreme edges) meets no ball
    not on. One array computation: the search judges thousands of simulated fouls a turn."""
    positions = balls.positions
    cue = positions[balls.index(CUE)]
    aims = positions[[balls.index(b) for b in present]]
    gap = aims - cue
    dist = np.maximum(np.hypot(gap[:, 0], gap[:, 1]), 1e-12)
    others = positions[balls.on_table & ~np.isin(balls.ids, [CUE, *present])]
    if len(others) == 0:
        return np.ones((len(offsets), len(present)), dtype=bool)
    r = table.ball_radius
    across = np.stack([-gap[:, 1], gap[:, 0]], axis=1) / dist[:, None]
    ends = (aims[None] + offsets[:, None, None] * 2 * r * across[None]).reshape(-1, 2) - cue
    length2 = np.sum(ends * ends, axis=1)
    length2[length2 == 0.0] = 1e-18
    t = np.clip(((others - cue) @ ends.T) / length2, 0.0, 1.0)
    nearest = cue + t[:, :, None] * ends[None, :, :]
    reach = 2 * r - 1e-9
    clear = np.all(np.sum((others[:, None, :] - nearest) ** 2, axis=2) >= reach * reach, axis=0)
    return np.asarray(clear, dtype=bool).reshape(len(offsets), len(present))


def snookered(table: Table, balls: BallSet, on: Sequence[int]) -> bool:
    """WPBSA Section 2, Rule 17: no ball on can be struck at both extreme edges
    (`edges_clear` asked of every ball on at once)."""
    present = _present(balls, on)
    if not present:
        return False
    return not bool(np.any(np.all(_clear_paths(table, balls, present, EDGES), axis=0)))


def open_path(table: Table, balls: BallSet, on: Sequence[int]) -> bool:
    """WPBSA Section 3, Rule 14: a clear path in a straight line from the cue ball to any
    part of any ball on (17 points across each ball, edge to edge; a sliver between them
    is taken as closed)."""
    present = _present(balls, on)
    if not present:
        return False
    return bool(np.any(_clear_paths(table, balls, present, ANY_PART)))


def _free(table: Table, balls: BallSet, ball: int, xy: tuple[float, float]) -> bool:
    x, y = xy
    if not table.contains(x, y):
        return False
    reach = 2 * table.ball_radius + SPOT_GAP
    on = balls.on_table & (balls.ids != ball)
    d2 = np.sum((balls.positions[on] - (x, y)) ** 2, axis=1)
    return bool(np.all(d2 >= reach * reach))


def spot_point(table: Table, balls: BallSet, ball: int) -> tuple[float, float]:
    """Where colour `ball` is re-spotted (WPBSA Section 3, Rule 7)."""
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
    raise ValueError("no free point on the line through the spot")  # needs more balls than exist


def respot_colours(table: Table, balls: BallSet, ball_ids: Iterable[int]) -> BallSet:
    """A copy of `balls` with each colour of `ball_ids` spotted (WPBSA 3.7): first those
    whose own spot is free, on it; then the others, the highest value first (it has
    precedence when their own spots are occupied)."""
    out = balls
    later = []
    for ball in sorted(ball_ids, key=VALUES.__getitem__, reverse=True):
        own = table.spots[NAMES[ball]]
        if _free(table, out, ball, own):
            out = out.with_ball(ball, own)
        else:
            later.append(ball)
    for ball in later:
        out = out.with_ball(ball, spot_point(table, out, ball))
    return out
