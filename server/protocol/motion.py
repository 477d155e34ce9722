"""A shot's exact motion, traced and packed into the binary `motion` message.

Why: the engine moves each ball in straight sub-steps that end at tick boundaries, at
friction changes and at every event (ball, cushion, jaw, pocket, rest). Frames at a fixed
rate cut every contact that falls between two of them (a cue ball drawn turning a ball's
width short of the rail). Here the shot is run again through the engine's own compiled
tick (`run_tick`: the tick `run_to_rest_kernel` runs, one at a time, at the same times, so
the ticks are the engine's bit for bit), and each tick holding events is replayed from its
start up to each event's time, which gives every ball's exact position there. Per ball, the samples
(tick ends and event times) are thinned to the knots a straight-line interpolation needs to
stay within `TOLERANCE` of all of them; knots at the ball's own events are always kept.

The message (docs/protocol.md, `motion`): a header, one track per ball (knots: time in
microseconds, position in 0.1 mm, rolled angle in 1/4096 turn; the first absolute, then
LEB128 varint deltas), then the sounds. Everything runs in compiled code without the GIL
except the few sounds.
"""

from __future__ import annotations

import functools
import math
import struct
from dataclasses import dataclass

import numpy as np
from numba import njit

from server.engine import DEFAULT_PARAMS, DEFAULT_TICK, BallSet, Event, Shot, ShotInMotion, Table
from server.engine.physics.constants import (
    EV_BALL,
    EV_CUSHION,
    EV_JAW,
    EV_POCKET,
    EV_REST,
    MAX_EVENTS_PER_TICK,
    POCKETED,
)
from server.engine.physics.tick import any_moving, cels_of, run_tick
from server.engine.simulate import MAX_SHOT_SECONDS

MOTION_KIND = 1  # first byte of every binary server message: which one it is
MOTION_VERSION = 1
POSITION_UNIT = 1e-4  # m: positions in 0.1 mm
TIME_UNIT = 1e-6  # s: times in microseconds
PHASE_STEPS = 4096  # rolled angle in 1/4096 of a turn (a sprite cel is 1/16)
TOLERANCE = 0.0002  # m: the knots' straight lines pass this close to every sample
PHASE_TOLERANCE = 0.03  # rad of roll
MAX_SPAN = 64  # samples between two knots at most (bounds the thinning's work)
MAX_REPLAYS = 24  # event times replayed per tick (pockets always): a rack's cascade has few
BEFORE = 1e-9  # s: a replay stops this short of its event (a pocket moves the ball away)
NO_BALL = 255
EVENT_ROWS = 4 * MAX_EVENTS_PER_TICK  # rows one tick may write (see `_trace`)
HEADER = struct.Struct("<BBIIIBH")  # kind, version, seq, shot, duration_us, balls, events
SEQ_OFFSET = 2
SOUND_CODES = {"strike": 0, "ball": 1, "cushion": 2, "jaw": 3, "pocket": 4}


@njit(cache=True, nogil=True)
def _trace(
    pos, vel, w, st, phase, pocket_of, cush, jaws, pockets, centers, length, width, p, dt,
    max_ticks,
):  # fmt: skip
    """Samples of the whole shot: t = 0, every event time (replayed), every tick's end; and
    what the engine's `run_to_rest_kernel` returns for the same shot, value for value (the
    same `run_tick` calls: the table is advanced to rest in place, as the engine does).

    Returns (times (S,), positions (S, N, 2), phases (S, N), on-table (S, N), forced
    (S, N): the ball takes part in an event at that sample, ticks, and the engine's
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
    s_on = np.empty((cap, n), dtype=np.bool_)
    s_forced = np.zeros((cap, n), dtype=np.bool_)
    # A tick stops after MAX_EVENTS_PER_TICK contacts, but the `rest` events between them
    # are not counted: a stalling cluster was seen writing 5,266 rows in one tick.
    events = np.empty((EVENT_ROWS, 6))
    scratch = np.empty((EVENT_ROWS, 6))
    # Snapshots of the table at each tick's start and for the replays, reused (a shot has
    # hundreds of ticks).
    pos0, vel0, w0, st0 = np.empty_like(pos), np.empty_like(vel), np.empty_like(w), st.copy()
    phase0, pocket0 = np.empty_like(phase), pocket_of.copy()
    pos1, vel1, w1, st1 = np.empty_like(pos), np.empty_like(vel), np.empty_like(w), st.copy()
    phase1, pocket1 = np.empty_like(phase), pocket_of.copy()
    k = 0
    s_t[0] = 0.0
    s_pos[0] = pos
    s_phase[0] = phase
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
        n_ev, stalled = run_tick(
            pos, vel, w, st, phase, pocket_of, cush, jaws, pockets, centers, length, width, p,
            dt, t0, events, 0,
        )  # fmt: skip
        if stalled:
            stalls += 1
        if ticks == frame_cap:
            frame_cap *= 2
            frame_pos = _grown(frame_pos, frame_cap)
            frame_cels = _grown(frame_cels, frame_cap)
            frame_on = _grown(frame_on, frame_cap)
        frame_pos[ticks] = pos
        cels_of(phase, st, frame_cels[ticks], p)
        for i in range(n):
            frame_on[ticks, i] = st[i] != POCKETED
        if n_rows + n_ev > rows.shape[0]:
            rows = _grown(rows, 2 * (n_rows + n_ev))
        rows[n_rows : n_rows + n_ev] = events[:n_ev]
        n_rows += n_ev
        if k + n_ev + 2 >= cap:
            cap = 2 * (k + n_ev + 2)
            s_t = _grown(s_t, cap)
            s_pos = _grown(s_pos, cap)
            s_phase = _grown(s_phase, cap)
            s_on = _grown(s_on, cap)
            s_forced = _grown(s_forced, cap)
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
                    run_tick(
                        pos1, vel1, w1, st1, phase1, pocket1, cush, jaws, pockets, centers,
                        length, width, p, span, t0, scratch, 0,
                    )  # fmt: skip
                    s_pos[k] = pos1
                    s_phase[k] = phase1
                    s_t[k] = time  # (the balls BEFORE earlier: the same within 1e-8 m)
                    for i in range(n):
                        # On the table up to its pocket event (the replay stops short).
                        s_on[k, i] = st1[i] != POCKETED
                else:
                    s_pos[k] = pos0
                    s_phase[k] = phase0
                    s_t[k] = t0
                    for i in range(n):
                        s_on[k, i] = st0[i] != POCKETED
                s_forced[k] = False
                for j in range(e, last):
                    kind = int(events[j, 1])
                    if kind == EV_BALL or kind == EV_CUSHION or kind == EV_JAW:  # noqa: SIM109
                        s_forced[k, int(events[j, 2])] = True
                        if kind == EV_BALL:
                            s_forced[k, int(events[j, 3])] = True
                    elif kind == EV_POCKET or kind == EV_REST:  # noqa: SIM109
                        s_forced[k, int(events[j, 2])] = True
                if s_t[k] > s_t[k - 1]:
                    k += 1
            e = last
        s_t[k] = t0 + dt
        s_pos[k] = pos
        s_phase[k] = phase
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
        ticks,
        engine,
    )


@njit(cache=True, nogil=True)
def _grown(a, rows):
    out = np.empty((rows,) + a.shape[1:], dtype=a.dtype)
    out[: a.shape[0]] = a
    return out


@njit(cache=True, inline="always")
def _fits(t, pos, phase, b, a, j, tol, tol_phase):
    """Does the straight line from sample a to sample j pass within tol of every sample
    between them (ball b)?"""
    span = t[j] - t[a]
    for i in range(a + 1, j):
        f = (t[i] - t[a]) / span if span > 0.0 else 0.0
        x = pos[a, b, 0] + (pos[j, b, 0] - pos[a, b, 0]) * f
        y = pos[a, b, 1] + (pos[j, b, 1] - pos[a, b, 1]) * f
        if (x - pos[i, b, 0]) ** 2 + (y - pos[i, b, 1]) ** 2 > tol * tol:
            return False
        ph = phase[a, b] + (phase[j, b] - phase[a, b]) * f
        if abs(ph - phase[i, b]) > tol_phase:
            return False
    return True


@njit(cache=True, nogil=True)
def _thin(t, pos, phase, on, forced, tol, tol_phase, max_span):
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
            while end > 0 and _same(pos, phase, b, end - 1, end):
                end -= 1
        knots[count] = 0
        count += 1
        a = 0
        while a < end:
            j = a + 1
            if _same(pos, phase, b, a, j):
                while j < end and _same(pos, phase, b, a, j + 1):
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
                if not _fits(t, pos, phase, b, a, probe, tol, tol_phase):
                    fails = probe
                    break
                j = probe
                step *= 2
            while fails - j > 1 and j < limit:
                mid = (j + fails) // 2
                if _fits(t, pos, phase, b, a, mid, tol, tol_phase):
                    j = mid
                else:
                    fails = mid
            knots[count] = j
            count += 1
            a = j
        offsets[b + 1] = count
    return knots[:count].copy(), offsets


@njit(cache=True, inline="always")
def _same(pos, phase, b, i, j):
    return (
        pos[i, b, 0] == pos[j, b, 0] and pos[i, b, 1] == pos[j, b, 1] and phase[i, b] == phase[j, b]
    )


@njit(cache=True, inline="always")
def _varint(buf, at, value):
    while value >= 128:
        buf[at] = (value & 127) | 128
        value >>= 7
        at += 1
    buf[at] = value
    return at + 1


@njit(cache=True, inline="always")
def _zigzag(buf, at, value):
    return _varint(buf, at, (value << 1) if value >= 0 else ((-value) << 1) - 1)


@njit(cache=True, nogil=True)
def pack_tracks(ids, pocket_of, t, pos, phase, knots, offsets):
    """The tracks section (see docs/protocol.md): per ball id, pocket, knot count, the first
    knot absolute, then varint deltas of time, x, y and roll."""
    n = ids.shape[0]
    buf = np.empty(16 * n + 16 * knots.shape[0], dtype=np.uint8)
    at = 0
    for b in range(n):
        lo, hi = offsets[b], offsets[b + 1]
        if hi == lo:
            continue
        buf[at] = ids[b]
        buf[at + 1] = pocket_of[b] if pocket_of[b] >= 0 else 255
        buf[at + 2] = (hi - lo) & 255
        buf[at + 3] = (hi - lo) >> 8
        at += 4
        prev_t = 0
        prev_x = 0
        prev_y = 0
        prev_p = 0
        for k in range(lo, hi):
            i = knots[k]
            tt = int(round(t[i] * 1e6))
            x = int(round(pos[i, b, 0] * 1e4))
            y = int(round(pos[i, b, 1] * 1e4))
            ph = int(round(phase[i, b] / (2.0 * math.pi) * 4096.0))
            if k == lo:
                at = _varint(buf, at, tt)
                first = ph % 4096
                x16 = x & 65535
                y16 = y & 65535
                buf[at] = x16 & 255
                buf[at + 1] = x16 >> 8
                buf[at + 2] = y16 & 255
                buf[at + 3] = y16 >> 8
                buf[at + 4] = first & 255
                buf[at + 5] = first >> 8
                at += 6
                prev_t, prev_x, prev_y, prev_p = tt, x, y, ph
            else:
                at = _varint(buf, at, tt - prev_t)
                at = _zigzag(buf, at, x - prev_x)
                at = _zigzag(buf, at, y - prev_y)
                at = _zigzag(buf, at, ph - prev_p)
                prev_t, prev_x, prev_y, prev_p = tt, x, y, ph
    return buf[:at].copy()


@dataclass(frozen=True)
class Tracks:
    """A traced shot: the samples and, per ball, the knots kept (see `_thin`)."""

    ids: np.ndarray
    times: np.ndarray  # (S,) s
    positions: np.ndarray  # (S, N, 2) m
    phases: np.ndarray  # (S, N) rad rolled
    on_table: np.ndarray  # (S, N)
    knots: np.ndarray
    offsets: np.ndarray
    pockets: np.ndarray  # (N,) pocket index or -1
    ticks: int
    packed: bytes  # the tracks section of the message


@njit(cache=True, nogil=True)
def _traced(
    ids, pos, vel, w, st, phase, pocket_of, cush, jaws, pockets, centers, length, width, p, dt,
    max_ticks, tol, tol_phase, max_span,
):  # fmt: skip
    """The shot run once: the engine's outputs and the traced, thinned, packed tracks, in
    one compiled call (a worker thread takes the GIL back once per shot: under load each
    hand-over waits for the busy event loop)."""
    t, positions, phases, on, forced, ticks, engine = _trace(
        pos, vel, w, st, phase, pocket_of, cush, jaws, pockets, centers, length, width, p, dt,
        max_ticks,
    )  # fmt: skip
    knots, offsets = _thin(t, positions, phases, on, forced, tol, tol_phase, max_span)
    packed = pack_tracks(ids, pocket_of, t, positions, phases, knots, offsets)
    return t, positions, phases, on, knots, offsets, ticks, packed, engine


@functools.cache
def _geometry(table: Table) -> tuple:
    """The table as the kernels take it, built once per table."""
    return (
        table.cushion_array(),
        table.jaw_array(),
        table.pocket_array(),
        table.pocket_centers(),
        float(table.length),
        float(table.width),
    )


_PARAMS = DEFAULT_PARAMS.array()
_MAX_TICKS = int(MAX_SHOT_SECONDS / DEFAULT_TICK)


def run_traced(table: Table, motion: ShotInMotion) -> Tracks:
    """`motion.run()` and the shot's tracks from one pass over its ticks: the engine's own
    `run_tick`, the tick `ShotInMotion.run` runs (same arrays, same order, same times),
    so `motion.result()` is then what it would have been, bit for bit (tested
    against `simulate`). Compiled, without the GIL: run it in a worker thread."""
    s = motion.state
    ids = s.ids.astype(np.int64)
    cush, jaws, pockets, centers, length, width = _geometry(table)
    t, positions, phases, on, knots, offsets, ticks, packed, engine = _traced(
        ids, s.positions, s.velocities, s.spins, s.states, s.phases, s.pockets, cush, jaws,
        pockets, centers, length, width, _PARAMS, motion.tick, _MAX_TICKS, TOLERANCE,
        PHASE_TOLERANCE, MAX_SPAN,
    )  # fmt: skip
    # What `ShotInMotion.run` would have stored: its result() builds the events and the
    # final table from it.
    motion._raw = engine  # noqa: SLF001
    return Tracks(
        ids, t, positions, phases, on, knots, offsets, s.pockets.copy(), ticks,
        packed.tobytes(),
    )  # fmt: skip


def trace(table: Table, balls: BallSet, shot: Shot) -> Tracks:
    """The tracks of a shot (tests, benchmarks): `run_traced` on a fresh `ShotInMotion`."""
    return run_traced(table, ShotInMotion(table, balls, shot))


def pack_sounds(sounds: list[Event]) -> bytes:
    """The sounds section: per sound, varint microseconds since the previous one, kind,
    the two ball ids (255: none), target (255: none), speed in mm/s (u16)."""
    out = bytearray()
    prev = 0
    for event in sounds:
        at = max(prev, int(round(event.time / TIME_UNIT)))
        _put_varint(out, at - prev)
        prev = at
        ids = list(event.ids) + [NO_BALL]
        target = event.target if 0 <= event.target < NO_BALL else NO_BALL
        speed = min(65535, max(0, int(round(event.speed * 1000))))
        out += struct.pack("<BBBBH", SOUND_CODES[event.kind], ids[0], ids[1], target, speed)
    return bytes(out)


def _put_varint(out: bytearray, value: int) -> None:
    while value >= 128:
        out.append((value & 127) | 128)
        value >>= 7
    out.append(value)


def motion_bytes(
    shot_id: int, duration: float, tracks: bytes, balls: int, sounds: list[Event]
) -> bytes:
    """The whole binary `motion` message, `seq` 0 (`with_seq` sets it per broadcast)."""
    head = HEADER.pack(
        MOTION_KIND,
        MOTION_VERSION,
        0,
        shot_id,
        int(round(duration / TIME_UNIT)),
        balls,
        len(sounds),
    )
    return head + tracks + pack_sounds(sounds)


def with_seq(message: bytes, seq: int) -> bytes:
    """The message with its room sequence number (bytes 2..5)."""
    return message[:SEQ_OFFSET] + struct.pack("<I", seq) + message[SEQ_OFFSET + 4 :]


SOUND_KINDS = tuple(SOUND_CODES)


def decode_motion(message: bytes) -> dict:
    """The binary `motion` message as plain values (tests, benchmarks, outside clients in
    Python): `type`, `seq`, `shot`, `duration` (s), `tracks` (per ball: `id`, `pocket`,
    knot `t` (s), `x`, `y` (m) and `phase` (rad rolled, from the first knot's angle)) and
    `sounds` (`t`, `kind`, `ids`, `speed`, `target`, as the engine's events)."""
    kind, version, seq, shot, duration, balls, count = HEADER.unpack_from(message)
    if kind != MOTION_KIND or version != MOTION_VERSION:
        raise ValueError(f"not a motion message of version {MOTION_VERSION}")
    at = HEADER.size
    tracks = []
    for _ in range(balls):
        ball, pocket, knots = struct.unpack_from("<BBH", message, at)
        at += 4
        t, at = _get_varint(message, at)
        x, y, phase = struct.unpack_from("<hhH", message, at)
        at += 6
        ts, xs, ys, phases = [t], [x], [y], [phase]
        for _ in range(knots - 1):
            dt, at = _get_varint(message, at)
            dx, at = _get_zigzag(message, at)
            dy, at = _get_zigzag(message, at)
            dp, at = _get_zigzag(message, at)
            ts.append(ts[-1] + dt)
            xs.append(xs[-1] + dx)
            ys.append(ys[-1] + dy)
            phases.append(phases[-1] + dp)
        tracks.append(
            {
                "id": ball,
                "pocket": None if pocket == NO_BALL else pocket,
                "t": [v / 1e6 for v in ts],
                "x": [v / 1e4 for v in xs],
                "y": [v / 1e4 for v in ys],
                "phase": [v * 2 * math.pi / PHASE_STEPS for v in phases],
            }
        )
    sounds = []
    time = 0
    for _ in range(count):
        dt, at = _get_varint(message, at)
        time += dt
        code, a, b, target, speed = struct.unpack_from("<BBBBH", message, at)
        at += 6
        sounds.append(
            {
                "t": time / 1e6,
                "kind": SOUND_KINDS[code],
                "ids": [a] if b == NO_BALL else [a, b],
                "speed": speed / 1000,
                "target": -1 if target == NO_BALL else target,
            }
        )
    if at != len(message):
        raise ValueError("trailing bytes after the motion message")
    return {
        "type": "motion",
        "seq": seq,
        "shot": shot,
        "duration": duration / 1e6,
        "tracks": tracks,
        "sounds": sounds,
    }


def _get_varint(data: bytes, at: int) -> tuple[int, int]:
    value = shift = 0
    while True:
        byte = data[at]
        at += 1
        value |= (byte & 127) << shift
        shift += 7
        if byte < 128:
            return value, at


def _get_zigzag(data: bytes, at: int) -> tuple[int, int]:
    value, at = _get_varint(data, at)
    return (value >> 1) ^ -(value & 1), at
