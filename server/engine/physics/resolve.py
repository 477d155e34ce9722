"""What an event does to the balls.

Ball-ball (Han & Zhu (2004) §1, eq. 5): normal components exchanged, tangential kept; with
restitution e the exchange is scaled by (1 + e)/2. Friction at the contact (Alciatore's
TP A-14 model) throws the object ball and passes spin between the balls.
Cushion and jaw: Han 2005's impulse model with the contact on the cushion nose, above the
ball's centre (see `rebound`), and a restitution that falls at high speed.
A flying ball: contacts in three dimensions (`ball_ball_3d`), over a cushion's nose it
leaves the table (`off_table`), and where it lands it drops into a hole or bounces (`land`).
"""

import math

from numba import njit

from .constants import (
    AIRBORNE,
    MIN_HOP_SPEED,
    OFF_TABLE,
    P_CUSHION_NOSE,
    P_E_BALL,
    P_E_CUSHION,
    P_E_CUSHION_KNEE,
    P_E_CUSHION_MIN,
    P_E_CUSHION_SLOPE,
    P_F_CUSHION,
    P_RADIUS,
    P_U_BALL_A,
    P_U_BALL_B,
    P_U_BALL_C,
    POCKETED,
    SLIDING,
)
from .motion import classify
from .vector import norm as _norm


@njit(cache=True)
def ball_ball(pos, vel, w, st, i, j, p):
    """Collide balls i and j; returns the approach speed along the line of centres (0 when
    they were not approaching, and nothing changed).

    Normal part: Han & Zhu (2004) §1 eq. 5, the exchange scaled by (1 + e)/2. Tangential part: one
    Coulomb friction impulse against the slip of the two surfaces at the contact point,
    at most mu times the normal impulse and never more than stops the slip (each surface
    point answers a tangential impulse J/m with 7/2 J/m, so the slip with 7 J/m), with
    mu = a + b exp(-c |slip|) (Alciatore, TP A-14). It throws the object ball off the line
    of centres (most for a slow stun cut; a rolling ball's topspin rubs vertically and
    throws less), turns the cue ball's path and passes spin across: side spin, and top
    or bottom spin from the vertical rub. Vertical impulse goes to the spin only (2-D).
    """
    dx = pos[j, 0] - pos[i, 0]
    dy = pos[j, 1] - pos[i, 1]
    d2 = dx * dx + dy * dy
    rel = (vel[i, 0] - vel[j, 0]) * dx + (vel[i, 1] - vel[j, 1]) * dy
    if rel <= 0.0 or d2 == 0.0:
        return 0.0
    d = math.sqrt(d2)
    nx, ny = dx / d, dy / d  # from i to j
    vn = rel / d
    jn = vn * (1.0 + p[P_E_BALL]) / 2.0
    radius = p[P_RADIUS]
    # Contact point velocities: i's at +R n, j's at -R n (w x r, n horizontal).
    ux = vel[i, 0] - vel[j, 0] - radius * (w[i, 2] + w[j, 2]) * ny
    uy = vel[i, 1] - vel[j, 1] + radius * (w[i, 2] + w[j, 2]) * nx
    uz = radius * ((w[i, 0] + w[j, 0]) * ny - (w[i, 1] + w[j, 1]) * nx)
    un = ux * nx + uy * ny
    sx, sy, sz = ux - un * nx, uy - un * ny, uz
    slip = math.sqrt(sx * sx + sy * sy + sz * sz)
    vel[i, 0] -= jn * nx
    vel[i, 1] -= jn * ny
    vel[j, 0] += jn * nx
    vel[j, 1] += jn * ny
    if slip > 0.0:
        mu = p[P_U_BALL_A] + p[P_U_BALL_B] * math.exp(-p[P_U_BALL_C] * slip)
        k = min(mu * jn, slip / 7.0) / slip
        # Friction impulse per unit mass on j is +F, on i is -F (F along the slip).
        fx, fy, fz = k * sx, k * sy, k * sz
        vel[i, 0] -= fx
        vel[i, 1] -= fy
        vel[j, 0] += fx
        vel[j, 1] += fy
        # Spin: i's lever is +R n and its impulse -F, j's -R n and +F: the same change
        # for both, -(5 / 2R) n x F.
        c = 2.5 / radius
        dwx = -c * (ny * fz)
        dwy = c * (nx * fz)
        dwz = -c * (nx * fy - ny * fx)
        w[i, 0] += dwx
        w[i, 1] += dwy
        w[i, 2] += dwz
        w[j, 0] += dwx
        w[j, 1] += dwy
        w[j, 2] += dwz
    classify(vel, w, st, i, radius)
    classify(vel, w, st, j, radius)
    return vn


@njit(cache=True, inline="always")
def cushion_restitution(vn, p):
    """Restitution at normal impact speed vn: constant up to the knee, then falling."""
    e = p[P_E_CUSHION]
    knee = p[P_E_CUSHION_KNEE]
    if vn > knee:
        e = max(e - p[P_E_CUSHION_SLOPE] * (vn - knee), p[P_E_CUSHION_MIN])
    return e


@njit(cache=True, inline="always")
def rebound(vel, w, st, i, nx, ny, p):
    """Bounce ball i off a cushion nose whose horizontal normal (nx, ny) points back at the
    ball; returns the normal impact speed (0 when the ball was moving away).

    Han 2005's rigid-cushion impulse model ("Dynamics in carom and three cushion
    billiards", J. Mech. Sci. Tech. 19(4)), as Mathavan et al. 2010 restate it: the nose
    touches the ball at height h above the bed, above the centre by R sin(theta),
    sin(theta) = h/R - 1, so the contact normal leans down into the ball by theta. One
    impulse at that point: along the contact normal (1 + e) times the approach speed
    there, v.d cos(theta); across it Coulomb friction against the contact point's slip,
    at most f_c times the normal impulse and never more than stops the slip (a sphere's
    surface point answers a tangential impulse J/m with 7/2 J/m). Top, draw and side spin
    all act through the rail. The bed takes the vertical part of the impulse (the engine
    is 2-D); the spin takes all of it. e falls with speed (`cushion_restitution`).
    """
    # d: horizontal unit vector from the centre towards the cushion.
    dx, dy = -nx, -ny
    vn = vel[i, 0] * dx + vel[i, 1] * dy
    if vn <= 0.0:
        return 0.0
    radius = p[P_RADIUS]
    sin_t = 2.0 * p[P_CUSHION_NOSE] - 1.0
    cos_t = math.sqrt(max(1.0 - sin_t * sin_t, 0.0))
    # Unit vector from the centre to the contact point, and the contact point's velocity
    # u = v + w x (R k).
    kx, ky, kz = cos_t * dx, cos_t * dy, sin_t
    wx, wy, wz = w[i, 0], w[i, 1], w[i, 2]
    ux = vel[i, 0] + radius * (wy * kz - wz * ky)
    uy = vel[i, 1] + radius * (wz * kx - wx * kz)
    uz = radius * (wx * ky - wy * kx)
    approach = vn * cos_t  # u.k: the rotation adds nothing along k
    jn = (1.0 + cushion_restitution(vn, p)) * approach
    # Slip across the contact normal.
    sx, sy, sz = ux - approach * kx, uy - approach * ky, uz - approach * kz
    slip = math.sqrt(sx * sx + sy * sy + sz * sz)
    # Impulse per unit mass on the ball: -jn k - jf s/|s| (its vertical part goes into the
    # bed and the spin).
    px, py = -jn * kx, -jn * ky
    if slip > 0.0:
        jf = min(p[P_F_CUSHION] * jn, slip / 3.5) / slip
        fx, fy, fz = -jf * sx, -jf * sy, -jf * sz
        px += fx
        py += fy
        # Spin: (m R k x F) / I with I = 2/5 m R^2.
        c = 2.5 / radius
        w[i, 0] += c * (ky * fz - kz * fy)
        w[i, 1] += c * (kz * fx - kx * fz)
        w[i, 2] += c * (kx * fy - ky * fx)
    vel[i, 0] += px
    vel[i, 1] += py
    classify(vel, w, st, i, radius)
    return vn


@njit(cache=True)
def cushion(vel, w, st, i, c, cush, p):
    return rebound(vel, w, st, i, cush[c, 4], cush[c, 5], p)


@njit(cache=True)
def jaw(pos, vel, w, st, i, k, jaws, p):
    """Ball i hits jaw k: its point (k < J, the normal from the point to the centre) or
    its facing (k - J, the facing's normal)."""
    n_jaws = jaws.shape[0]
    if k >= n_jaws:
        return rebound(vel, w, st, i, jaws[k - n_jaws, 4], jaws[k - n_jaws, 5], p)
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


@njit(cache=True, inline="always")
def flying(air, i):
    """Is ball i off the bed (above it, or leaving it upwards)?"""
    return air[i, 0] > 0.0 or air[i, 1] > 0.0


@njit(cache=True)
def ball_ball_3d(pos, vel, w, st, air, i, j, p):
    """Collide balls i and j when one of them flies: one impulse along the line of centres
    in three dimensions that sends them apart at e times their approach speed. A ball on
    the bed pushed down by it is held by the slate (it takes only the horizontal part, so
    the impulse is solved with that ball's vertical motion locked); one pushed up is
    lifted. No friction at this contact. Returns the approach speed (0 when not
    approaching)."""
    dx = pos[j, 0] - pos[i, 0]
    dy = pos[j, 1] - pos[i, 1]
    dz = air[j, 0] - air[i, 0]
    d2 = dx * dx + dy * dy + dz * dz
    rel = (vel[i, 0] - vel[j, 0]) * dx + (vel[i, 1] - vel[j, 1]) * dy + (air[i, 1] - air[j, 1]) * dz
    if rel <= 0.0 or d2 == 0.0:
        return 0.0
    d = math.sqrt(d2)
    nx, ny, nz = dx / d, dy / d, dz / d  # from i to j
    vn = rel / d
    flat = nx * nx + ny * ny
    # i takes -J n, j takes +J n: a ball on the bed pushed down keeps no vertical part.
    lift_i = 0.0 if (air[i, 0] <= 0.0 and nz > 0.0) else 1.0
    lift_j = 0.0 if (air[j, 0] <= 0.0 and nz < 0.0) else 1.0
    jn = (1.0 + p[P_E_BALL]) * vn / (2.0 * flat + (lift_i + lift_j) * nz * nz)
    vel[i, 0] -= jn * nx
    vel[i, 1] -= jn * ny
    air[i, 1] -= lift_i * jn * nz
    vel[j, 0] += jn * nx
    vel[j, 1] += jn * ny
    air[j, 1] += lift_j * jn * nz
    settle_height(vel, w, st, air, i, p[P_RADIUS])
    settle_height(vel, w, st, air, j, p[P_RADIUS])
    return vn


@njit(cache=True, inline="always")
def settle_height(vel, w, st, air, i, radius):
    """After a contact: a ball on the bed pushed down stays on it (the slate takes the
    push), one lifted by less than MIN_HOP_SPEED too; anything else flies."""
    if air[i, 0] <= 0.0 and air[i, 1] < MIN_HOP_SPEED:
        air[i, 0] = 0.0
        air[i, 1] = 0.0
        if st[i] == AIRBORNE:
            st[i] = SLIDING
        classify(vel, w, st, i, radius)
    else:
        st[i] = AIRBORNE


@njit(cache=True)
def off_table(vel, w, st, air, pocket_of, i):
    """Ball i flies over a cushion's nose: it is out of play where it crossed (state
    POCKETED, pocket OFF_TABLE). Returns its speed."""
    speed = _norm(vel[i, 0], vel[i, 1])
    st[i] = POCKETED
    pocket_of[i] = OFF_TABLE
    for a in range(2):
        vel[i, a] = 0.0
        air[i, a] = 0.0
    for a in range(3):
        w[i, a] = 0.0
    return speed


@njit(cache=True, inline="always")
def over_hole(pos, i, pockets):
    """The pocket whose hole ball i's centre is over, or -1."""
    for k in range(pockets.shape[0]):
        if _norm(pos[i, 0] - pockets[k, 0], pos[i, 1] - pockets[k, 1]) < pockets[k, 2]:
            return k
    return -1
