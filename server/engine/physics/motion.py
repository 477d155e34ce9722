"""How a ball moves between events: sliding, rolling and spinning friction.

Within one sub-step a ball moves in a straight line at the velocity it has at the start of
the sub-step (Han & Zhu's (2004) model), and its velocity and spin are then brought forward
exactly under constant friction. Sub-steps end at every state change (slide to roll, roll
to rest), so the friction law never changes inside one.

Sliding: the contact point slips with u = v + w x (-R z); friction -u_s g u/|u| slows it
and turns the ball, and |u| falls at 7/2 u_s g, so sliding ends after 2|u|/(7 u_s g).
Rolling: deceleration u_r g along v, w = z x v / R. Spin about z decays at 5 u_sp g / 2R.
"""

import math

from numba import njit

from .constants import (
    EPS_SPEED,
    EPS_SPIN,
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


# Inlined into the tick loop (see `tick.run_ticks`).
@njit(cache=True, inline="always")
def advance(pos, vel, w, st, phase, n, dt, p):
    """Move every ball on the table forward by dt (no events may occur inside dt)."""
    radius = p[P_RADIUS]
    spin_decel = 2.5 * p[P_U_SPIN] * p[P_G] / radius
    for i in range(n):
        s = st[i]
        if s == POCKETED or s == STATIONARY:
            continue
        vx, vy = vel[i, 0], vel[i, 1]
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
def strike_ball(vel, w, st, i, vx, vy, wx, wy, wz, radius):
    """Give ball i a strike's velocity (vx, vy) and spin (wx, wy, wz), and the motion
    state they make."""
    vel[i, 0] = vx
    vel[i, 1] = vy
    w[i, 0] = wx
    w[i, 1] = wy
    w[i, 2] = wz
    classify(vel, w, st, i, radius)
