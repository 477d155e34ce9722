"""What an event does to the balls.

Ball-ball (paper §1, eq. 5): normal components exchanged, tangential kept; with restitution
e the exchange is scaled by (1 + e)/2. Spins are untouched (no ball-ball friction).
Cushion and jaw: the normal velocity is reversed and scaled by the cushion restitution; a
friction impulse at the contact (at most f_c times the normal impulse, and never more than
stops the slip) lets side spin bend the rebound and wears the spin down.
"""

import math

from numba import njit

from .constants import P_E_BALL, P_E_CUSHION, P_F_CUSHION, P_RADIUS, POCKETED
from .motion import classify
from .vector import norm as _norm


@njit(cache=True)
def ball_ball(pos, vel, w, st, i, j, p):
    """Collide balls i and j; returns the approach speed along the line of centres (0 when
    they were not approaching, and nothing changed)."""
    dx = pos[i, 0] - pos[j, 0]
    dy = pos[i, 1] - pos[j, 1]
    d2 = dx * dx + dy * dy
    rel = (vel[i, 0] - vel[j, 0]) * dx + (vel[i, 1] - vel[j, 1]) * dy
    if rel >= 0.0 or d2 == 0.0:
        return 0.0
    k = rel / d2 * (1.0 + p[P_E_BALL]) / 2.0
    vel[i, 0] -= k * dx
    vel[i, 1] -= k * dy
    vel[j, 0] += k * dx
    vel[j, 1] += k * dy
    classify(vel, w, st, i, p[P_RADIUS])
    classify(vel, w, st, j, p[P_RADIUS])
    return -rel / math.sqrt(d2)


@njit(cache=True, inline="always")
def rebound(vel, w, st, i, nx, ny, p):
    """Bounce ball i off a surface with unit normal (nx, ny) pointing back at the ball;
    returns the normal impact speed (0 when the ball was moving away)."""
    vn = vel[i, 0] * nx + vel[i, 1] * ny
    if vn >= 0.0:
        return 0.0
    radius = p[P_RADIUS]
    e = p[P_E_CUSHION]
    vel[i, 0] -= (1.0 + e) * vn * nx
    vel[i, 1] -= (1.0 + e) * vn * ny
    # Friction along the cushion, t = z x n; contact point velocity v.t - R wz.
    tx, ty = -ny, nx
    slip_t = vel[i, 0] * tx + vel[i, 1] * ty - radius * w[i, 2]
    # Impulses per unit mass: normal (1 + e)|vn|; slip changes by 3.5 per unit of friction.
    jt = min(p[P_F_CUSHION] * (1.0 + e) * -vn, abs(slip_t) / 3.5)
    if slip_t > 0.0:
        jt = -jt
    vel[i, 0] += jt * tx
    vel[i, 1] += jt * ty
    w[i, 2] -= jt / (0.4 * radius)
    classify(vel, w, st, i, radius)
    return -vn


@njit(cache=True)
def cushion(vel, w, st, i, c, cush, p):
    return rebound(vel, w, st, i, cush[c, 4], cush[c, 5], p)


@njit(cache=True)
def jaw(pos, vel, w, st, i, k, jaws, p):
    dx = pos[i, 0] - jaws[k, 0]
    dy = pos[i, 1] - jaws[k, 1]
    d = _norm(dx, dy)
    if d == 0.0:
        return 0.0
    return rebound(vel, w, st, i, dx / d, dy / d, p)


@njit(cache=True)
def pocket(pos, vel, w, st, pocket_of, i, k, centers):
    """Ball i drops into pocket k: it leaves play and rests at the pocket's centre."""
    speed = _norm(vel[i, 0], vel[i, 1])
    st[i] = POCKETED
    pocket_of[i] = k
    pos[i, 0] = centers[k, 0]
    pos[i, 1] = centers[k, 1]
    for a in range(2):
        vel[i, a] = 0.0
    for a in range(3):
        w[i, a] = 0.0
    return speed
