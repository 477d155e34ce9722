"""How a ball moves between events: sliding, rolling and spinning friction.

Within one sub-step a ball moves in a straight line at the velocity it has at the start of
the sub-step (Han & Zhu's (2004) model), and its velocity and spin are then brought forward
exactly under constant friction. Sub-steps end at every state change (slide to roll, roll
to rest), so the friction law never changes inside one.

Sliding: the contact point slips with u = v + w x (-R z); friction -u_s g u/|u| slows it
and turns the ball, and |u| falls at 7/2 u_s g, so sliding ends after 2|u|/(7 u_s g).
Rolling: deceleration u_r g along v, w = z x v / R. Spin about z decays at 5 u_sp g / 2R.
Airborne (a jump or a hop): no friction; the height follows the parabola exactly,
z + vz t - g t^2 / 2, and the flight ends at the exact landing time (`landing_time`).
"""

import math

from numba import njit

from .constants import (
    AIRBORNE,
    E_SLATE,
    EPS_SPEED,
    EPS_SPIN,
    MIN_HOP_SPEED,
    P_G,
    P_RADIUS,
    P_U_ROLL,
    P_U_SLIDE,
    P_U_SPIN,
    POCKETED,
    ROLLING,
    SLIDING,
    SPINNING,
    STATIONARY,
)
from .vector import norm as _norm


@njit(cache=True, inline="always")
def slip(vel, w, i, radius):
    """Velocity of ball i's contact point with the cloth."""
    return vel[i, 0] - radius * w[i, 1], vel[i, 1] + radius * w[i, 0]


@njit(cache=True, inline="always")
def classify(vel, w, st, i, radius):
    """Set ball i's motion state from its velocity and spin (snapping tiny values to zero)."""
    if st[i] == POCKETED:
        return
    sx, sy = slip(vel, w, i, radius)
    speed = _norm(vel[i, 0], vel[i, 1])
    if _norm(sx, sy) > EPS_SPEED:
        st[i] = SLIDING
    elif speed > EPS_SPEED:
        st[i] = ROLLING
        w[i, 0] = -vel[i, 1] / radius
        w[i, 1] = vel[i, 0] / radius
    else:
        vel[i, 0] = 0.0
        vel[i, 1] = 0.0
        w[i, 0] = 0.0
        w[i, 1] = 0.0
        st[i] = SPINNING if abs(w[i, 2]) > EPS_SPIN else STATIONARY


@njit(cache=True, inline="always")
def transition_time(state, vx, vy, wx, wy, p):
    """Time until a ball changes its friction law (inf when it will not). Scalars only:
    array arguments cost a reference count per call in the hot loop."""
    if state == SLIDING:
        radius = p[P_RADIUS]
        return _norm(vx - radius * wy, vy + radius * wx) / (3.5 * p[P_U_SLIDE] * p[P_G])
    if state == ROLLING:
        return _norm(vx, vy) / (p[P_U_ROLL] * p[P_G])
    return math.inf


@njit(cache=True, inline="always")
def landing_time(z, vz, g):
    """Time until a flying ball's height z (moving at vz) is back to 0 under g."""
    return (vz + math.sqrt(max(vz * vz + 2.0 * g * z, 0.0))) / g


# Inlined into the tick loop (see `tick.run_ticks`).
@njit(cache=True, inline="always")
def advance(pos, vel, w, st, phase, air, n, dt, p):
    """Move every ball on the table forward by dt (no events may occur inside dt)."""
    radius = p[P_RADIUS]
    spin_decel = 2.5 * p[P_U_SPIN] * p[P_G] / radius
    for i in range(n):
        s = st[i]
        if s == POCKETED or s == STATIONARY:
            continue
        vx, vy = vel[i, 0], vel[i, 1]
        if s == AIRBORNE:
            pos[i, 0] += vx * dt
            pos[i, 1] += vy * dt
            speed = _norm(vx, vy)
            if speed > 0.0:
                phase[i] += (w[i, 1] * vx - w[i, 0] * vy) / speed * dt
            g = p[P_G]
            air[i, 0] += (air[i, 1] - 0.5 * g * dt) * dt
            air[i, 1] -= g * dt
            continue
        if s == SLIDING or s == ROLLING:
            pos[i, 0] += vx * dt
            pos[i, 1] += vy * dt
            speed = _norm(vx, vy)
            if speed > 0.0:
                phase[i] += (w[i, 1] * vx - w[i, 0] * vy) / speed * dt
        if s == SLIDING:
            sx, sy = slip(vel, w, i, radius)
            u = _norm(sx, sy)
            ax = -p[P_U_SLIDE] * p[P_G] * sx / u
            ay = -p[P_U_SLIDE] * p[P_G] * sy / u
            vel[i, 0] += ax * dt
            vel[i, 1] += ay * dt
            w[i, 0] += 2.5 * ay / radius * dt
            w[i, 1] += -2.5 * ax / radius * dt
        elif s == ROLLING:
            speed = _norm(vx, vy)
            new_speed = max(speed - p[P_U_ROLL] * p[P_G] * dt, 0.0)
            scale = new_speed / speed
            vel[i, 0] = vx * scale
            vel[i, 1] = vy * scale
            w[i, 0] = -vel[i, 1] / radius
            w[i, 1] = vel[i, 0] / radius
        wz = w[i, 2]
        if wz != 0.0:
            mag = max(abs(wz) - spin_decel * dt, 0.0)
            w[i, 2] = mag if wz > 0.0 else -mag
        if s == SPINNING and w[i, 2] == 0.0:
            st[i] = STATIONARY


@njit(cache=True, inline="always")
def finish_transition(vel, w, st, i, radius):
    """Ball i has reached the end of its sliding or rolling phase: snap it to the next one.

    Returns True when the ball came to rest (a "rest" event)."""
    if st[i] == SLIDING:
        return classify_after_slide(vel, w, st, i, radius)
    if st[i] == ROLLING:
        vel[i, 0] = 0.0
        vel[i, 1] = 0.0
        w[i, 0] = 0.0
        w[i, 1] = 0.0
        st[i] = SPINNING if abs(w[i, 2]) > EPS_SPIN else STATIONARY
        return True
    return False


@njit(cache=True, inline="always")
def classify_after_slide(vel, w, st, i, radius):
    """The slip has reached zero: the ball rolls, or stops if it has no speed left (True)."""
    if _norm(vel[i, 0], vel[i, 1]) > EPS_SPEED:
        st[i] = ROLLING
        w[i, 0] = -vel[i, 1] / radius
        w[i, 1] = vel[i, 0] / radius
        return False
    vel[i, 0] = 0.0
    vel[i, 1] = 0.0
    w[i, 0] = 0.0
    w[i, 1] = 0.0
    st[i] = SPINNING if abs(w[i, 2]) > EPS_SPIN else STATIONARY
    return True


@njit(cache=True, inline="always")
def drop_residual_spin(w, st):
    """A ball that has stopped translating keeps spinning about the vertical a little
    while, which cannot move it any more: a shot's final table drops that spin."""
    for i in range(st.shape[0]):
        if st[i] == SPINNING:
            w[i, 0] = 0.0
            w[i, 1] = 0.0
            w[i, 2] = 0.0
            st[i] = STATIONARY


@njit(cache=True, inline="always")
def strike_ball(vel, w, st, air, i, vx, vy, wx, wy, wz, down, p):
    """Give ball i a strike's velocity (vx, vy) and spin (wx, wy, wz), and the motion
    state they make; `down` (m/s) is the part driven into the slate by a raised cue, which
    bounces the ball up (`bounce`). A level strike (down = 0) is only the first part."""
    vel[i, 0] = vx
    vel[i, 1] = vy
    w[i, 0] = wx
    w[i, 1] = wy
    w[i, 2] = wz
    classify(vel, w, st, i, p[P_RADIUS])
    if down > 0.0:
        air[i, 0] = 0.0
        air[i, 1] = -down
        bounce(vel, w, st, air, i, p, False)


@njit(cache=True, inline="always")
def bounce(vel, w, st, air, i, p, friction):
    """Ball i meets the slate moving down at -air[i, 1]: it comes back up at E_SLATE times
    that speed, or stays down when that is under MIN_HOP_SPEED. With `friction` (a
    landing) the slate's friction (u_slide, Coulomb, at most what stops the contact's
    slip: a sphere's contact point answers a horizontal impulse J/m with 7/2 J/m) acts on
    the slip v + w x (-R z) during the impact; at the strike it does not (the cue and the
    slate act at once, and TP A.30's strike, pooltool's too, has the velocity and spin
    leave the cue as they are). Returns the speed of the impact (m/s, down)."""
    radius = p[P_RADIUS]
    down = -air[i, 1]
    if down <= 0.0:
        return 0.0
    sx = vel[i, 0] - radius * w[i, 1]
    sy = vel[i, 1] + radius * w[i, 0]
    slip = _norm(sx, sy)
    if friction and slip > 0.0:
        jf = min(p[P_U_SLIDE] * (1.0 + E_SLATE) * down, slip / 3.5) / slip
        ax, ay = -jf * sx, -jf * sy
        vel[i, 0] += ax
        vel[i, 1] += ay
        w[i, 0] += 2.5 * ay / radius
        w[i, 1] += -2.5 * ax / radius
    up = E_SLATE * down
    air[i, 0] = 0.0
    if up < MIN_HOP_SPEED:
        air[i, 1] = 0.0
        st[i] = STATIONARY
        classify(vel, w, st, i, radius)
    else:
        air[i, 1] = up
        st[i] = AIRBORNE
    return down
