"""Re-spotting an object ball: on the foot spot, or the nearest free point on the long
string behind it (towards the foot cushion); in front of it only if that line is full."""

from __future__ import annotations

import math

from server.engine import BallSet, Table

SPOT_GAP = 1e-5  # m left between a spotted ball and a ball it is frozen to


def _blocked(table: Table, balls: BallSet, ball_id: int) -> list[tuple[float, float]]:
    """x intervals of the long string where a ball centre would overlap another ball."""
    r2 = 2 * table.ball_radius + SPOT_GAP
    y0 = table.width / 2
    out = []
    for ball in balls.on_table_ids():
        if ball == ball_id:
            continue
        bx, by = balls.position_of(ball)
        dy = abs(by - y0)
        if dy < r2:
            half = math.sqrt(r2 * r2 - dy * dy)
            out.append((bx - half, bx + half))
    return out


def spot_point(table: Table, balls: BallSet, ball_id: int) -> tuple[float, float]:
    """Where `ball_id` goes back on the table (the foot spot, else along the long string)."""
    fx, y0 = table.foot_spot
    lo, hi = table.ball_radius, table.length - table.ball_radius
    intervals = _blocked(table, balls, ball_id)

    def free(x: float) -> bool:
        return lo <= x <= hi and all(not (a < x < b) for a, b in intervals)

    if free(fx):
        return (fx, y0)
    behind = sorted(b for a, b in intervals if b > fx and free(b))
    if behind:
        return (behind[0], y0)
    ahead = sorted((a for a, b in intervals if a < fx and free(a)), reverse=True)
    if ahead:
        return (ahead[0], y0)
    raise ValueError("no free point on the long string")  # needs more balls than exist


def respot(table: Table, balls: BallSet, ball_ids: tuple[int, ...]) -> BallSet:
    """A copy of `balls` with each of `ball_ids` (lowest first) spotted."""
    out = balls
    for ball in sorted(ball_ids):
        out = out.with_ball(ball, spot_point(table, out, ball))
    return out
