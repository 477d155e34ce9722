"""The fixed-tick loop: inside each tick, advance to the earliest event, resolve it, repeat.

A sub-step ends at the earliest of: the end of the tick, the next change of a ball's
friction law, the next collision. Events resolved at the same instant (a rack's touching
balls) follow one another at zero time; a pair that is already separating is no event, so
the cascade ends. Events are written into caller-owned arrays.
"""

import math

import numpy as np
from numba import njit

from .borrow import borrowed
from .constants import (
    AIRBORNE,
    EPS_SPIN,
    EV_BALL,
    EV_CUSHION,
    EV_JAW,
    EV_LAND,
    EV_NONE,
    EV_OFF,
    EV_POCKET,
    EV_REST,
    MAX_EVENTS_PER_TICK,
    P_CELS,
    P_CUSHION_NOSE,
    P_G,
    P_RADIUS,
    POCKETED,
    ROLLING,
    SLIDING,
    SPINNING,
    STATIONARY,
)
from .detect import earliest_event
from .motion import (
    advance,
    bounce,
    drop_residual_spin,
    finish_transition,
    landing_time,
    strike_ball,
    transition_time,
)
from .resolve import ball_ball, ball_ball_3d, cushion, jaw, off_table, over_hole, pocket
from .vector import norm as _norm


@njit(cache=True, inline="always")
def _record(events, n_ev, time, kind, a, b, speed, target):
    """Append an event row. A stalling cluster can write more rows in one tick than its
    caller keeps free (its `rest` events are not counted against MAX_EVENTS_PER_TICK);
    compiled code has no bounds check, so a full buffer drops the row instead of writing
    past the end."""
    if n_ev >= events.shape[0]:
        return n_ev
    events[n_ev, 0] = time
    events[n_ev, 1] = kind
    events[n_ev, 2] = a
    events[n_ev, 3] = b
    events[n_ev, 4] = speed
    events[n_ev, 5] = target
    return n_ev + 1


@njit(cache=True, nogil=True)
def run_tick(
    pos,
    vel,
    w,
    st,
    phase,
    pocket_of,
    air,
    cush,
    jaws,
    pockets,
    centers,
    length,
    width,
    p,
    dt,
    t0,
    events,
    n_ev,
):
    """Advance the table by one tick of length dt starting at time t0.

    events: (E, 6) float64 rows (time, kind, row a, row b, speed, target); n_ev rows are
    used. Returns (n_ev, stalled): stalled is True when the tick hit MAX_EVENTS_PER_TICK
    and stopped early (the balls are left where they are: no overlap).
    """
    n_ev, stalls, _ = run_ticks(
        pos, vel, w, st, phase, pocket_of, air, cush, jaws, pockets, centers, length, width, p,
        dt, t0, 0, 1, False, events, n_ev, 0, None, None, None,
    )  # fmt: skip
    return n_ev, stalls > 0


@njit(cache=True, nogil=True)
def run_ticks(
    pos,
    vel,
    w,
    st,
    phase,
    pocket_of,
    air,
    cush,
    jaws,
    pockets,
    centers,
    length,
    width,
    p,
    dt,
    t_start,
    ticks,
    last_tick,
    until_rest,
    events,
    n_ev,
    free_rows,
    frame_pos,
    frame_cels,
    frame_on,
):
    """Ticks `ticks`, `ticks` + 1, ... (tick k starts at t_start + k dt) up to `last_tick`,
    stopping early once no ball moves (with `until_rest`), before a tick when fewer than
    `free_rows` event rows are free, or when the frame arrays are full (the caller grows
    them and calls again; None for no frames: numba compiles that case without them).
    The tick loop and each tick's work are in one function, handing its helpers ownerless
    views of the arrays (`borrow`), because numba reference-counts the arrays of every
    compiled call, even an inlined one, with atomic operations: per tick, with a dozen
    arrays, that was first about half of a search's shot, then over a third of it.

    Each frame is the table at the end of its tick. Returns (n_ev, stalls,
    ticks): the event rows used, the ticks that stalled (hit MAX_EVENTS_PER_TICK and
    stopped early, the balls left where they are: no overlap), the next tick's number."""
    # Ownerless views: the helpers below are handed these on every sub-step (`borrow`).
    pos, vel, w = borrowed(pos), borrowed(vel), borrowed(w)
    st, phase, pocket_of = borrowed(st), borrowed(phase), borrowed(pocket_of)
    air = borrowed(air)
    cush, jaws, pockets = borrowed(cush), borrowed(jaws), borrowed(pockets)
    centers, p, events = borrowed(centers), borrowed(p), borrowed(events)
    n = pos.shape[0]
    radius = p[P_RADIUS]
    nose_height = 2.0 * radius * p[P_CUSHION_NOSE]  # a ball whose bottom is higher clears it
    stalls = 0
    while ticks < last_tick and (not until_rest or any_moving(st)):
        if events.shape[0] - n_ev < free_rows:
            break
        if frame_pos is not None and ticks == frame_pos.shape[0]:
            break
        t0 = t_start + ticks * dt
        stalled = False
        elapsed = 0.0
        count = 0
        first_ev = n_ev
        while elapsed < dt:
            remaining = dt - elapsed
            horizon = remaining
            for i in range(n):
                if st[i] == SLIDING or st[i] == ROLLING:
                    tt = transition_time(st[i], vel[i, 0], vel[i, 1], w[i, 0], w[i, 1], p)
                    if tt < horizon:
                        horizon = tt
                elif st[i] == AIRBORNE:
                    tt = landing_time(air[i, 0], air[i, 1], p[P_G])
                    if tt < horizon:
                        horizon = tt
            t, kind, a, b = earliest_event(
                pos, vel, st, air, n, horizon, cush, jaws, pockets, length, width, p
            )
            if kind != EV_NONE:
                advance(pos, vel, w, st, phase, air, n, t, p)
                elapsed += t
                now = t0 + elapsed
                if kind == EV_BALL:
                    if st[a] == AIRBORNE or st[b] == AIRBORNE:
                        speed = ball_ball_3d(pos, vel, w, st, air, a, b, p)
                    else:
                        speed = ball_ball(pos, vel, w, st, a, b, p)
                    if speed > 0.0:
                        n_ev = _record(events, n_ev, now, EV_BALL, a, b, speed, -1)
                elif st[a] == AIRBORNE and air[a, 0] >= nose_height:
                    # Over the nose of a cushion or a pocket's facing: off the table.
                    target = b if kind == EV_CUSHION or b < jaws.shape[0] else b - jaws.shape[0]
                    speed = off_table(vel, w, st, air, pocket_of, a)
                    n_ev = _record(events, n_ev, now, EV_OFF, a, -1, speed, target)
                elif kind == EV_CUSHION:
                    was_flying = st[a] == AIRBORNE
                    speed = cushion(vel, w, st, a, b, cush, p)
                    if was_flying:
                        st[a] = AIRBORNE
                    if speed > 0.0:
                        n_ev = _record(events, n_ev, now, EV_CUSHION, a, -1, speed, b)
                elif kind == EV_JAW:
                    was_flying = st[a] == AIRBORNE
                    speed = jaw(pos, vel, w, st, a, b, jaws, p)
                    if was_flying:
                        st[a] = AIRBORNE
                    if speed > 0.0:
                        target = b if b < jaws.shape[0] else b - jaws.shape[0]
                        n_ev = _record(events, n_ev, now, EV_JAW, a, -1, speed, target)
                else:
                    speed = pocket(pos, vel, w, st, pocket_of, a, b, centers)
                    n_ev = _record(events, n_ev, now, EV_POCKET, a, -1, speed, b)
                count += 1
                if count >= MAX_EVENTS_PER_TICK:
                    # A Zeno loop: e.g. a spinning ball pressed against a still one collides
                    # again at once, forever. Stop the balls of this event so the shot ends.
                    n_ev = _distinct(events, first_ev, n_ev)
                    n_ev = _halt(vel, w, st, a, now, events, n_ev)
                    if kind == EV_BALL:
                        n_ev = _halt(vel, w, st, b, now, events, n_ev)
                    stalled = True
                    break
                continue
            # No collision before the horizon: move there and finish any state change.
            advance(pos, vel, w, st, phase, air, n, horizon, p)
            if horizon >= remaining:
                elapsed = dt
            else:
                elapsed += horizon
            now = t0 + elapsed
            # After advancing exactly to a transition, round-off can leave a sliver of slip or
            # speed: a ball within a nanosecond of its transition has reached it.
            for i in range(n):
                if st[i] == AIRBORNE:
                    if landing_time(air[i, 0], air[i, 1], p[P_G]) <= 1e-9:
                        n_ev = _land(
                            pos, vel, w, st, air, pocket_of, i, pockets, centers, length,
                            width, p, now, events, n_ev,
                        )  # fmt: skip
                    continue
                if st[i] != SLIDING and st[i] != ROLLING:
                    continue
                tt = transition_time(st[i], vel[i, 0], vel[i, 1], w[i, 0], w[i, 1], p)
                if tt <= 1e-9 and finish_transition(vel, w, st, i, radius):
                    n_ev = _record(events, n_ev, now, EV_REST, i, -1, 0.0, -1)
        if stalled:
            stalls += 1
        if frame_pos is not None:
            frame_pos[ticks] = pos
            cels_of(phase, frame_cels[ticks], p)
            for i in range(n):
                frame_on[ticks, i] = st[i] != POCKETED
        ticks += 1
    return n_ev, stalls, ticks


@njit(cache=True, inline="always")
def _land(
    pos, vel, w, st, air, pocket_of, i, pockets, centers, length, width, p, now, events, n_ev
):
    """Ball i comes down: into the hole it is over, off the table when it is past the
    cushions and no pocket's shelf (within 2R of the hole) is under it, else a bounce on
    the bed (`bounce`: up again, or down for good). Records a `pocket`, an `off_table` or
    a `land` event."""
    air[i, 0] = 0.0
    k = over_hole(pos, i, pockets)
    if k >= 0:
        air[i, 1] = 0.0
        speed = pocket(pos, vel, w, st, pocket_of, i, k, centers)
        return _record(events, n_ev, now, EV_POCKET, i, -1, speed, k)
    x, y = pos[i, 0], pos[i, 1]
    if not (0.0 <= x <= length and 0.0 <= y <= width):
        shelf = False
        for k in range(pockets.shape[0]):
            reach = pockets[k, 2] + 2.0 * p[P_RADIUS]
            shelf = shelf or _norm(x - pockets[k, 0], y - pockets[k, 1]) < reach
        if not shelf:
            speed = off_table(vel, w, st, air, pocket_of, i)
            return _record(events, n_ev, now, EV_OFF, i, -1, speed, -1)
    speed = bounce(vel, w, st, air, i, p, True)
    return _record(events, n_ev, now, EV_LAND, i, -1, speed, -1)


@njit(cache=True)
def _distinct(events, start, n_ev):
    """Keep the first of each (kind, balls, target) among events[start:n_ev]: a stalled
    tick's thousands of repeats are one sound."""
    kept = start
    for e in range(start, n_ev):
        seen = False
        for k in range(start, kept):
            if (
                events[k, 1] == events[e, 1]
                and events[k, 2] == events[e, 2]
                and events[k, 3] == events[e, 3]
                and events[k, 5] == events[e, 5]
            ):
                seen = True
                break
        if not seen:
            events[kept] = events[e]
            kept += 1
    return kept


@njit(cache=True)
def _halt(vel, w, st, i, now, events, n_ev):
    """Bring ball i to rest (keeping its spin about the vertical) and record it."""
    if st[i] != SLIDING and st[i] != ROLLING:
        return n_ev
    vel[i, 0] = 0.0
    vel[i, 1] = 0.0
    w[i, 0] = 0.0
    w[i, 1] = 0.0
    st[i] = SPINNING if abs(w[i, 2]) > EPS_SPIN else STATIONARY
    return _record(events, n_ev, now, EV_REST, i, -1, 0.0, -1)


@njit(cache=True, inline="always")
def any_moving(st):
    for s in st:
        if s == SLIDING or s == ROLLING or s == AIRBORNE:
            return True
    return False


@njit(cache=True)
def cels_of(phase, out, p):
    n_cels = int(p[P_CELS])
    two_pi = 2.0 * math.pi
    for i in range(phase.shape[0]):
        turns = phase[i] / two_pi
        out[i] = int(math.floor((turns - math.floor(turns)) * n_cels)) % n_cels


@njit(cache=True, nogil=True)
def run_to_rest_kernel(
    pos,
    vel,
    w,
    st,
    phase,
    pocket_of,
    air,
    cush,
    jaws,
    pockets,
    centers,
    length,
    width,
    p,
    dt,
    max_ticks,
    event_capacity,
    frames,
):
    """A whole shot in one compiled call, so a thread running it holds the GIL only to
    enter and to return (the server's event loop needs it for everything else).

    With `frames` False no frame is recorded (the frame arrays come back empty): the ticks
    are the same, so are the events and the final table, bit for bit. The computer's
    search asks only where the balls stop, thousands of times a turn, and a frame every
    tick cost about a third of its short shots.

    The frame and event arrays grow by doubling. The event rows are not zeroed: only the
    rows written are read.
    Returns (frame_pos, frame_cels, frame_on, events, stalls, ticks)."""
    n = pos.shape[0]
    cap = 256 if frames else 0
    frame_pos = np.empty((cap, n, 2))
    frame_cels = np.empty((cap, n), dtype=np.int64)
    frame_on = np.empty((cap, n), dtype=np.bool_)
    events = np.empty((max(event_capacity, MAX_EVENTS_PER_TICK + 128), 6))
    ticks = 0
    n_ev = 0
    stalls = 0
    while ticks < max_ticks and any_moving(st):
        if frames and ticks == cap:
            cap *= 2
            frame_pos = grown(frame_pos, cap)
            frame_cels = grown(frame_cels, cap)
            frame_on = grown(frame_on, cap)
        if events.shape[0] - n_ev <= MAX_EVENTS_PER_TICK + 64:
            events = grown(events, 2 * events.shape[0])
        # Two calls, not one with chosen arguments: numba types the frames' arrays and
        # their absence (None) as two versions of run_ticks, which cannot share a call.
        if frames:
            n_ev, more_stalls, ticks = run_ticks(
                pos, vel, w, st, phase, pocket_of, air, cush, jaws, pockets, centers, length, width,
                p, dt, 0.0, ticks, max_ticks, True, events, n_ev, MAX_EVENTS_PER_TICK + 65,
                frame_pos, frame_cels, frame_on,
            )  # fmt: skip
        else:
            n_ev, more_stalls, ticks = run_ticks(
                pos, vel, w, st, phase, pocket_of, air, cush, jaws, pockets, centers, length, width,
                p, dt, 0.0, ticks, max_ticks, True, events, n_ev, MAX_EVENTS_PER_TICK + 65,
                None, None, None,
            )  # fmt: skip
        stalls += more_stalls
    kept = ticks if frames else 0
    return (
        frame_pos[:kept].copy(),
        frame_cels[:kept].copy(),
        frame_on[:kept].copy(),
        events[:n_ev].copy(),
        stalls,
        ticks,
    )


@njit(cache=True, nogil=True)
def settle_kernel(
    pos,
    vel,
    w,
    st,
    phase,
    pocket_of,
    air,
    cue,
    vx,
    vy,
    wx,
    wy,
    wz,
    down,
    cush,
    jaws,
    pockets,
    centers,
    length,
    width,
    p,
    dt,
    max_ticks,
    event_capacity,
):
    """A shot to rest without frames, from strike to final table, in one compiled call:
    copies of the balls' arrays (the caller's stay as they are), the cue ball given the
    strike's velocity (vx, vy), spin (wx, wy, wz) and speed `down` into the slate, the
    ticks, and the spin of a ball that no longer translates dropped. The same steps in
    Python (copies, strike, spin) cost about 15 us a shot, some 5 % of a search's short
    shot, and a search settles thousands a turn.
    Returns (pos, vel, w, st, phase, pocket_of, air, events, stalls, ticks)."""
    pos = pos.copy()
    vel = vel.copy()
    w = w.copy()
    st = st.copy()
    phase = phase.copy()
    pocket_of = pocket_of.copy()
    air = air.copy()
    strike_ball(vel, w, st, air, cue, vx, vy, wx, wy, wz, down, p)
    _, _, _, events, stalls, ticks = run_to_rest_kernel(
        pos, vel, w, st, phase, pocket_of, air, cush, jaws, pockets, centers, length, width, p,
        dt, max_ticks, event_capacity, False,
    )  # fmt: skip
    drop_residual_spin(w, st)
    return pos, vel, w, st, phase, pocket_of, air, events, stalls, ticks


@njit(cache=True, nogil=True)
def grown(a, rows):
    out = np.empty((rows,) + a.shape[1:], dtype=a.dtype)
    out[: a.shape[0]] = a
    return out


def empty_events(capacity: int) -> np.ndarray:
    return np.zeros((capacity, 6), dtype=np.float64)
