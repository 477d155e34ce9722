"""When does the next event happen? Times of impact for straight-line motion.

Ball-ball (Han & Zhu (2004) §2): with relative position d and velocity v the centres are 2R
apart when A t^2 + B t + C = 0, A = v.v, B = 2 d.v, C = d.d - (2R)^2. Only approaching pairs
(B < 0) can collide; an approaching pair that already touches or overlaps by round-off (C <= 0)
collides now. The smaller root is taken in the cancellation-free form 2C / (-B + sqrt(disc)).
A jaw point is the same quadratic with R in place of 2R, and a pocket's hole the same with
the hole's radius (the ball drops when its centre is over the hole); a cushion and a jaw's
facing are segments, so their times are linear.
A pair with a flying ball uses the same quadratic in three dimensions, its height moving
on the tangent of its parabola within the sub-step (off by at most g dt^2 / 2, 0.34 mm in
a tick: a touch that close is resolved at once, as an overlap by round-off is). A flying
ball meets the rails as any ball does, and no hole: it drops only where it lands.
"""

import math

from numba import njit

from .constants import (
    AIRBORNE,
    EV_BALL,
    EV_CUSHION,
    EV_JAW,
    EV_NONE,
    EV_POCKET,
    P_RADIUS,
    POCKETED,
    ROLLING,
    SLIDING,
)
from .vector import norm as _norm


@njit(cache=True, inline="always")
def quadratic_contact_time(dx, dy, vx, vy, reach):
    """Earliest t >= 0 at which |d + v t| = reach, for an approaching pair; inf if never."""
    b = 2.0 * (dx * vx + dy * vy)
    if b >= 0.0:
        return math.inf
    c = dx * dx + dy * dy - reach * reach
    if c <= 0.0:
        return 0.0
    a = vx * vx + vy * vy
    disc = b * b - 4.0 * a * c
    if disc < 0.0:
        return math.inf
    return 2.0 * c / (-b + math.sqrt(disc))


@njit(cache=True, inline="always")
def sphere_contact_time(dx, dy, dz, vx, vy, vz, reach):
    """`quadratic_contact_time` in three dimensions."""
    b = 2.0 * (dx * vx + dy * vy + dz * vz)
    if b >= 0.0:
        return math.inf
    c = dx * dx + dy * dy + dz * dz - reach * reach
    if c <= 0.0:
        return 0.0
    a = vx * vx + vy * vy + vz * vz
    disc = b * b - 4.0 * a * c
    if disc < 0.0:
        return math.inf
    return 2.0 * c / (-b + math.sqrt(disc))


@njit(cache=True, inline="always")
def line_contact_time(px, py, vx, vy, qx, qy, nx, ny, offset):
    """Earliest t >= 0 at which the signed distance (p + v t - q).n falls to `offset`."""
    vn = vx * nx + vy * ny
    if vn >= 0.0:
        return math.inf
    dist = (px - qx) * nx + (py - qy) * ny - offset
    if dist <= 0.0:
        return 0.0
    return dist / -vn


@njit(cache=True, inline="always")
def _moving(s):
    return s == SLIDING or s == ROLLING or s == AIRBORNE


# Inlined into the tick loop (see `tick.run_ticks`).
@njit(cache=True, inline="always")
def earliest_event(pos, vel, st, air, n, horizon, cush, jaws, pockets, length, width, p):
    """The first collision of any kind within `horizon` seconds.

    Returns (time, kind, a, b): kind is EV_NONE when nothing happens in time; a is a ball
    row; b is the other ball's row, or the cushion / jaw / pocket index (a jaw's facing is
    its index plus the number of jaws).
    """
    radius = p[P_RADIUS]
    best_t = math.inf
    kind = EV_NONE
    best_a = -1
    best_b = -1
    for i in range(n):
        si = st[i]
        if not _moving(si):
            continue
        px, py = pos[i, 0], pos[i, 1]
        vx, vy = vel[i, 0], vel[i, 1]
        limit = min(best_t, horizon)
        # Balls: pairs with a stationary partner are found here, moving pairs once (i < j).
        for j in range(n):
            if j == i or st[j] == POCKETED:
                continue
            if _moving(st[j]) and j < i:
                continue
            dx = px - pos[j, 0]
            dy = py - pos[j, 1]
            rvx = vx - vel[j, 0]
            rvy = vy - vel[j, 1]
            gap = _norm(dx, dy) - 2.0 * radius
            if gap > _norm(rvx, rvy) * limit + 1e-9:
                continue
            if si == AIRBORNE or st[j] == AIRBORNE:
                t = sphere_contact_time(
                    dx, dy, air[i, 0] - air[j, 0], rvx, rvy, air[i, 1] - air[j, 1], 2.0 * radius
                )
            else:
                t = quadratic_contact_time(dx, dy, rvx, rvy, 2.0 * radius)
            if t <= limit and t < best_t:
                best_t, kind, best_a, best_b = t, EV_BALL, i, j
                limit = t
        # Rails, jaws and pockets only matter near the edge of the bed.
        reach = _norm(vx, vy) * limit + 1e-9
        if (
            2.0 * radius + reach < px < length - 2.0 * radius - reach
            and 2.0 * radius + reach < py < width - 2.0 * radius - reach
        ):
            continue
        for c in range(cush.shape[0]):
            t = line_contact_time(
                px, py, vx, vy, cush[c, 0], cush[c, 1], cush[c, 4], cush[c, 5], radius
            )
            if t <= limit and t < best_t:
                # The contact point must lie on the segment; past its ends the jaw is hit.
                cx = px + vx * t - cush[c, 0]
                cy = py + vy * t - cush[c, 1]
                tx = cush[c, 2] - cush[c, 0]
                ty = cush[c, 3] - cush[c, 1]
                along = (cx * tx + cy * ty) / (tx * tx + ty * ty)
                if 0.0 <= along <= 1.0:
                    best_t, kind, best_a, best_b = t, EV_CUSHION, i, c
                    limit = t
        n_jaws = jaws.shape[0]
        for k in range(n_jaws):
            jx, jy = jaws[k, 0], jaws[k, 1]
            t = quadratic_contact_time(px - jx, py - jy, vx, vy, radius)
            if t <= limit and t < best_t:
                best_t, kind, best_a, best_b = t, EV_JAW, i, k
                limit = t
            # The facing behind the point: a segment like a cushion (target k + n_jaws).
            t = line_contact_time(px, py, vx, vy, jx, jy, jaws[k, 4], jaws[k, 5], radius)
            if t <= limit and t < best_t:
                cx = px + vx * t - jx
                cy = py + vy * t - jy
                tx = jaws[k, 2] - jx
                ty = jaws[k, 3] - jy
                along = (cx * tx + cy * ty) / (tx * tx + ty * ty)
                if 0.0 <= along <= 1.0:
                    best_t, kind, best_a, best_b = t, EV_JAW, i, k + n_jaws
                    limit = t
        if si == AIRBORNE:
            continue
        for k in range(pockets.shape[0]):
            # The centre comes over the hole.
            t = quadratic_contact_time(
                px - pockets[k, 0], py - pockets[k, 1], vx, vy, pockets[k, 2]
            )
            if t <= limit and t < best_t:
                best_t, kind, best_a, best_b = t, EV_POCKET, i, k
                limit = t
    return best_t, kind, best_a, best_b
