"""A shot's exact tracks, from the same compiled call that simulates it.

Why: the engine moves each ball in straight sub-steps that end at tick boundaries, at
friction changes and at every event (ball, cushion, jaw, pocket, rest). Frames at a fixed
rate cut every contact that falls between two of them (a cue ball drawn turning a ball's
width short of the rail). `traced_run_kernel` runs the shot tick by tick through `run_tick`
(the tick `run_to_rest_kernel` runs, at the same times, so the ticks, events and final
table are the engine's bit for bit) and replays each tick holding events from its start
up to each event's time, which gives every ball's exact position there. Per ball, the
samples (tick ends and event times) are then thinned to the knots a straight-line
interpolation needs to stay within a tolerance of all of them; knots at the ball's own
events are always kept. One call without the GIL does it all: a thread running a shot
takes the GIL back once.
"""

import numpy as np
from numba import njit

from .constants import (
    EV_BALL,
    EV_CUSHION,
    EV_JAW,
    EV_POCKET,
    EV_REST,
    MAX_EVENTS_PER_TICK,
    POCKETED,
)
from .tick import any_moving, cels_of, grown, run_tick

MAX_SPAN = 64  # samples between two knots at most (bounds the thinning's work)
MAX_REPLAYS = 24  # event times replayed per tick (pockets always): a rack's cascade has few
BEFORE = 1e-9  # s: a replay stops this short of its event (a pocket moves the ball away)
EVENT_ROWS = 4 * MAX_EVENTS_PER_TICK  # rows one tick may write (see `trace_ticks`)


@njit(cache=True, nogil=True)
def traced_run_kernel(
    pos, vel, w, st, phase, pocket_of, air, cush, jaws, pockets, centers, length, width, p,
    dt, max_ticks, tol, tol_phase,
):  # fmt: skip
    """The shot run to rest once, traced and thinned, in one compiled call. The table is
    advanced in place, as `run_to_rest_kernel` advances it.

    Returns (times (S,), positions (S, N, 2), phases (S, N), on-table (S, N), knots,
    offsets (see `thin`), heights (S, N), ticks, and what `run_to_rest_kernel` returns
    for the same shot,
    value for value: (frame positions, frame cels, frame on-table, event rows, stalled
    ticks, ticks))."""
    t, positions, phases, on, forced, heights, ticks, engine = trace_ticks(
        pos, vel, w, st, phase, pocket_of, air, cush, jaws, pockets, centers, length, width, p,
        dt, max_ticks,
    )  # fmt: skip
    knots, offsets = thin(t, positions, phases, heights, on, forced, tol, tol_phase, MAX_SPAN)
    return t, positions, phases, on, knots, offsets, heights, ticks, engine


@njit(cache=True, nogil=True)
def trace_ticks(
    pos, vel, w, st, phase, pocket_of, air, cush, jaws, pockets, centers, length, width, p,
    dt, max_ticks,
):  # fmt: skip
    """Samples of the whole shot: t = 0, every event time (replayed), every tick's end; and
    what the engine's `run_to_rest_kernel` returns for the same shot, value for value (the
    same `run_tick` calls: the table is advanced to rest in place, as the engine does).

    Returns (times (S,), positions (S, N, 2), phases (S, N), on-table (S, N), forced
    (S, N): the ball takes part in an event at that sample, heights (S, N), ticks, and
    the engine's
    (frame positions, frame cels, frame on-table, event rows, stalled ticks, ticks))."""
    n = pos.shape[0]
    frame_cap = 256
    frame_pos = np.empty((frame_cap, n, 2))
    frame_cels = np.empty((frame_cap, n), dtype=np.int64)
    frame_on = np.empty((frame_cap, n), dtype=np.bool_)
    rows = np.empty((4096, 6))
    n_rows = 0
    stalls = 0
    cap = 1024
    s_t = np.empty(cap)
    s_pos = np.empty((cap, n, 2))
    s_phase = np.empty((cap, n))
    s_z = np.zeros((cap, n))
    s_on = np.empty((cap, n), dtype=np.bool_)
    s_forced = np.zeros((cap, n), dtype=np.bool_)
    # A tick stops after MAX_EVENTS_PER_TICK contacts, but the `rest` events between them
    # are not counted: a stalling cluster was seen writing 5,266 rows in one tick.
    events = np.empty((EVENT_ROWS, 6))
    scratch = np.empty((EVENT_ROWS, 6))
    # Snapshots of the table at each tick's start and for the replays, reused (a shot has
    # hundreds of ticks).
    pos0, vel0, w0, st0 = np.empty_like(pos), np.empty_like(vel), np.empty_like(w), st.copy()
    phase0, pocket0, air0 = np.empty_like(phase), pocket_of.copy(), air.copy()
    pos1, vel1, w1, st1 = np.empty_like(pos), np.empty_like(vel), np.empty_like(w), st.copy()
    phase1, pocket1, air1 = np.empty_like(phase), pocket_of.copy(), air.copy()
    k = 0
    s_t[0] = 0.0
    s_pos[0] = pos
    s_phase[0] = phase
    s_z[0] = air[:, 0]
    for i in range(n):
        s_on[0, i] = st[i] != POCKETED
    k = 1
    ticks = 0
    while ticks < max_ticks and any_moving(st):
        t0 = ticks * dt
        pos0[:] = pos
        vel0[:] = vel
        w0[:] = w
        st0[:] = st
        phase0[:] = phase
        pocket0[:] = pocket_of
        air0[:] = air
        n_ev, stalled = run_tick(
            pos, vel, w, st, phase, pocket_of, air, cush, jaws, pockets, centers, length,
            width, p, dt, t0, events, 0,
        )  # fmt: skip
        if stalled:
            stalls += 1
        if ticks == frame_cap:
            frame_cap *= 2
            frame_pos = grown(frame_pos, frame_cap)
            frame_cels = grown(frame_cels, frame_cap)
            frame_on = grown(frame_on, frame_cap)
        frame_pos[ticks] = pos
        cels_of(phase, frame_cels[ticks], p)
        for i in range(n):
            frame_on[ticks, i] = st[i] != POCKETED
        if n_rows + n_ev > rows.shape[0]:
            rows = grown(rows, 2 * (n_rows + n_ev))
        rows[n_rows : n_rows + n_ev] = events[:n_ev]
        n_rows += n_ev
        if k + n_ev + 2 >= cap:
            cap = 2 * (k + n_ev + 2)
            s_t = grown(s_t, cap)
            s_pos = grown(s_pos, cap)
            s_phase = grown(s_phase, cap)
            s_z = grown(s_z, cap)
            s_on = grown(s_on, cap)
            s_forced = grown(s_forced, cap)
            s_forced[k:] = False
        e = 0
        replays = 0
        while e < n_ev:
            time = events[e, 0]
            last = e
            has_pocket = False
            while last < n_ev and events[last, 0] == time:
                has_pocket = has_pocket or events[last, 1] == EV_POCKET
                last += 1
            if replays < MAX_REPLAYS or has_pocket:
                replays += 1
                span = time - t0 - BEFORE
                if span > 0.0:
                    pos1[:] = pos0
                    vel1[:] = vel0
                    w1[:] = w0
                    st1[:] = st0
                    phase1[:] = phase0
                    pocket1[:] = pocket0
                    air1[:] = air0
                    run_tick(
                        pos1, vel1, w1, st1, phase1, pocket1, air1, cush, jaws, pockets,
                        centers, length, width, p, span, t0, scratch, 0,
                    )  # fmt: skip
                    s_pos[k] = pos1
                    s_phase[k] = phase1
                    s_z[k] = air1[:, 0]
                    s_t[k] = time  # (the balls BEFORE earlier: the same within 1e-8 m)
                    for i in range(n):
                        # On the table up to its pocket event (the replay stops short).
                        s_on[k, i] = st1[i] != POCKETED
                else:
                    s_pos[k] = pos0
                    s_phase[k] = phase0
                    s_z[k] = air0[:, 0]
                    s_t[k] = t0
                    for i in range(n):
                        s_on[k, i] = st0[i] != POCKETED
                s_forced[k] = False
                for j in range(e, last):
                    kind = int(events[j, 1])
                    if kind == EV_BALL or kind == EV_CUSHION or kind == EV_JAW:
                        s_forced[k, int(events[j, 2])] = True
                        if kind == EV_BALL:
                            s_forced[k, int(events[j, 3])] = True
                    elif kind == EV_POCKET or kind == EV_REST:
                        s_forced[k, int(events[j, 2])] = True
                if s_t[k] > s_t[k - 1]:
                    k += 1
            e = last
        s_t[k] = t0 + dt
        s_pos[k] = pos
        s_phase[k] = phase
        s_z[k] = air[:, 0]
        s_forced[k] = False
        for i in range(n):
            s_on[k, i] = st[i] != POCKETED
        k += 1
        ticks += 1
    engine = (
        frame_pos[:ticks].copy(),
        frame_cels[:ticks].copy(),
        frame_on[:ticks].copy(),
        rows[:n_rows].copy(),
        stalls,
        ticks,
    )
    return (
        s_t[:k].copy(),
        s_pos[:k].copy(),
        s_phase[:k].copy(),
        s_on[:k].copy(),
        s_forced[:k].copy(),
        s_z[:k].copy(),
        ticks,
        engine,
    )


@njit(cache=True, inline="always")
def _fits(t, pos, phase, z, b, a, j, tol, tol_phase):
    """Does the straight line from sample a to sample j pass within tol of every sample
    between them (ball b), its height too?"""
    span = t[j] - t[a]
    for i in range(a + 1, j):
        f = (t[i] - t[a]) / span if span > 0.0 else 0.0
        x = pos[a, b, 0] + (pos[j, b, 0] - pos[a, b, 0]) * f
        y = pos[a, b, 1] + (pos[j, b, 1] - pos[a, b, 1]) * f
        if (x - pos[i, b, 0]) ** 2 + (y - pos[i, b, 1]) ** 2 > tol * tol:
            return False
        if abs(z[a, b] + (z[j, b] - z[a, b]) * f - z[i, b]) > tol:
            return False
        ph = phase[a, b] + (phase[j, b] - phase[a, b]) * f
        if abs(ph - phase[i, b]) > tol_phase:
            return False
    return True


@njit(cache=True, nogil=True)
def thin(t, pos, phase, z, on, forced, tol, tol_phase, max_span):
    """Knot sample indices per ball: (knots, offsets) with ball b's in
    knots[offsets[b]:offsets[b + 1]]. A ball's track ends at its last sample on the table
    (its pocket) or where it last moved (it rests there after)."""
    s, n = on.shape
    knots = np.empty(s * n, dtype=np.int64)
    offsets = np.zeros(n + 1, dtype=np.int64)
    count = 0
    for b in range(n):
        end = -1  # last sample on the table
        for i in range(s):
            if on[i, b]:
                end = i
        if end < 0:
            offsets[b + 1] = count
            continue
        if end == s - 1:  # never pocketed: it rests where it last moved
            while end > 0 and _same(pos, phase, z, b, end - 1, end):
                end -= 1
        knots[count] = 0
        count += 1
        a = 0
        while a < end:
            j = a + 1
            if _same(pos, phase, z, b, a, j):
                while j < end and _same(pos, phase, z, b, a, j + 1):
                    j += 1
                knots[count] = j
                count += 1
                a = j
                continue
            # The furthest the next knot may be: the end, MAX_SPAN on, or the ball's next
            # contact (a knot itself). The line a -> a + 1 always fits; gallop, then halve.
            limit = j
            while limit < end and limit - a < max_span and not forced[limit, b]:
                limit += 1
            step = 1
            fails = limit + 1
            while j < limit:
                probe = min(j + step, limit)
                if not _fits(t, pos, phase, z, b, a, probe, tol, tol_phase):
                    fails = probe
                    break
                j = probe
                step *= 2
            while fails - j > 1 and j < limit:
                mid = (j + fails) // 2
                if _fits(t, pos, phase, z, b, a, mid, tol, tol_phase):
                    j = mid
                else:
                    fails = mid
            knots[count] = j
            count += 1
            a = j
        offsets[b + 1] = count
    return knots[:count].copy(), offsets


@njit(cache=True, inline="always")
def _same(pos, phase, z, b, i, j):
    return (
        pos[i, b, 0] == pos[j, b, 0]
        and pos[i, b, 1] == pos[j, b, 1]
        and phase[i, b] == phase[j, b]
        and z[i, b] == z[j, b]
    )
