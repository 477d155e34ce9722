"""A shot's motion packed into the binary `motion` message.

The engine traces the shot in the same compiled call that simulates it
(`ShotInMotion.run(trace=...)`: per ball, knots at its contacts and wherever a straight line
would stray more than the tolerance). Here the knots are quantised and packed: a header,
one track per ball (knots: time in microseconds, position in 0.1 mm, rolled angle in 1/4096
turn, and in version 2 the height in 0.1 mm; the first absolute, then LEB128 varint
deltas), then the sounds (docs/protocol.md, `motion`). A shot where no ball leaves the bed
is version 1, byte for byte as before heights existed; one with a jump or a hop is
version 2. The packing is compiled too but keeps the GIL: it takes microseconds, and
releasing the GIL would make a shot's thread win it back a second time.
"""

from __future__ import annotations

import math
import struct
from dataclasses import dataclass
from typing import Any

import numpy as np
from numba import njit

from server.engine import BallSet, Event, Shot, ShotInMotion, Table, Tolerance, Trace

MOTION_KIND = 1  # first byte of every binary server message: which one it is
MOTION_VERSION = 1  # no ball leaves the bed
MOTION_VERSION_HEIGHTS = 2  # every knot also has the ball's height
OFF_TABLE_POCKET = 254  # version 2: the ball flew off the table (255: it stays on it)
POSITION_UNIT = 1e-4  # m: positions in 0.1 mm
TIME_UNIT = 1e-6  # s: times in microseconds
PHASE_STEPS = 4096  # rolled angle in 1/4096 of a turn (a sprite cel is 1/16)
TOLERANCE = 0.0002  # m: the knots' straight lines pass this close to every sample
PHASE_TOLERANCE = 0.03  # rad of roll
TRACE = Tolerance(TOLERANCE, PHASE_TOLERANCE)
NO_BALL = 255
HEADER = struct.Struct("<BBIIIBH")  # kind, version, seq, shot, duration_us, balls, events
SEQ_OFFSET = 2
# `land` (a flying ball meets the slate) only happens in a version 2 message.
SOUND_CODES = {"strike": 0, "ball": 1, "cushion": 2, "jaw": 3, "pocket": 4, "land": 5}


@njit(cache=True, inline="always")
def _varint(buf: np.ndarray, at: int, value: int) -> int:
    while value >= 128:
        buf[at] = (value & 127) | 128
        value >>= 7
        at += 1
    buf[at] = value
    return at + 1


@njit(cache=True, inline="always")
def _zigzag(buf: np.ndarray, at: int, value: int) -> int:
    return _varint(buf, at, (value << 1) if value >= 0 else ((-value) << 1) - 1)


@njit(cache=True, inline="always")
def _first_knot(
    buf: np.ndarray, at: int, tt: int, x: int, y: int, ph: int, zz: int, with_z: bool
) -> int:
    """A track's first knot: varint time, x and y as i16, roll as u16, height as u16."""
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
    if with_z:
        z16 = min(zz, 65535)
        buf[at] = z16 & 255
        buf[at + 1] = z16 >> 8
        at += 2
    return at


@njit(cache=True)
def pack_tracks(
    ids: np.ndarray,
    pocket_of: np.ndarray,
    t: np.ndarray,
    pos: np.ndarray,
    phase: np.ndarray,
    knots: np.ndarray,
    offsets: np.ndarray,
    z: np.ndarray,
    with_z: bool,
) -> np.ndarray:
    """The tracks section (see docs/protocol.md): per ball id, pocket, knot count, the first
    knot absolute, then varint deltas of time, x, y and roll, and `with_z` (version 2) of
    the height too. Holds the GIL (see above)."""
    n = ids.shape[0]
    buf = np.empty(16 * n + 20 * knots.shape[0], dtype=np.uint8)
    at = 0
    for b in range(n):
        lo, hi = offsets[b], offsets[b + 1]
        if hi == lo:
            continue
        buf[at] = ids[b]
        if pocket_of[b] >= 0:
            buf[at + 1] = pocket_of[b]
        elif pocket_of[b] == -2 and with_z:
            buf[at + 1] = 254
        else:
            buf[at + 1] = 255
        buf[at + 2] = (hi - lo) & 255
        buf[at + 3] = (hi - lo) >> 8
        at += 4
        prev_t = 0
        prev_x = 0
        prev_y = 0
        prev_p = 0
        prev_z = 0
        for k in range(lo, hi):
            i = knots[k]
            tt = int(round(t[i] * 1e6))  # noqa: RUF046 (the compiled type)
            x = int(round(pos[i, b, 0] * 1e4))  # noqa: RUF046 (the compiled type)
            y = int(round(pos[i, b, 1] * 1e4))  # noqa: RUF046 (the compiled type)
            ph = int(round(phase[i, b] / (2.0 * math.pi) * 4096.0))  # noqa: RUF046 (the compiled type)
            zz = max(int(round(z[i, b] * 1e4)), 0)  # noqa: RUF046 (the compiled type)
            if k == lo:
                at = _first_knot(buf, at, tt, x, y, ph, zz, with_z)
                prev_t, prev_x, prev_y, prev_p, prev_z = tt, x, y, ph, zz
            else:
                at = _varint(buf, at, tt - prev_t)
                at = _zigzag(buf, at, x - prev_x)
                at = _zigzag(buf, at, y - prev_y)
                at = _zigzag(buf, at, ph - prev_p)
                if with_z:
                    at = _zigzag(buf, at, zz - prev_z)
                prev_t, prev_x, prev_y, prev_p, prev_z = tt, x, y, ph, zz
    return buf[:at].copy()


@dataclass(frozen=True)
class Tracks:
    """A traced shot (the engine's `Trace`: its samples and, per ball, the knots kept) and
    its tracks section packed."""

    ids: np.ndarray
    times: np.ndarray  # (S,) s
    positions: np.ndarray  # (S, N, 2) m
    phases: np.ndarray  # (S, N) rad rolled
    on_table: np.ndarray  # (S, N)
    knots: np.ndarray
    offsets: np.ndarray
    pockets: np.ndarray  # (N,) pocket index, -1, or OFF_TABLE (-2)
    ticks: int
    packed: bytes  # the tracks section of the message
    version: int = MOTION_VERSION  # MOTION_VERSION_HEIGHTS when some ball flies


def tracks_of(trace: Trace) -> Tracks:
    """The trace with its tracks section packed (with heights when some ball flies)."""
    flies = trace.flies
    heights = trace.heights if trace.heights is not None else np.zeros(trace.phases.shape)
    packed = pack_tracks(
        trace.ids, trace.pockets, trace.times, trace.positions, trace.phases, trace.knots,
        trace.offsets, heights, flies,
    )  # fmt: skip
    version = MOTION_VERSION_HEIGHTS if flies else MOTION_VERSION
    return Tracks(
        trace.ids, trace.times, trace.positions, trace.phases, trace.on_table, trace.knots,
        trace.offsets, trace.pockets, trace.ticks, packed.tobytes(), version,
    )  # fmt: skip


def run_traced(motion: ShotInMotion) -> Tracks:
    """`motion.run()` traced within `TRACE`, and its tracks packed: one compiled call that
    releases the GIL (the engine's), then the packing, which keeps it. `motion.result()`
    is then what it would have been, bit for bit. Run it in a worker thread."""
    motion.run(trace=TRACE)
    return tracks_of(motion.trace)


def trace(table: Table, balls: BallSet, shot: Shot) -> Tracks:
    """The tracks of a shot (tests, benchmarks): `run_traced` on a fresh `ShotInMotion`."""
    return run_traced(ShotInMotion(table, balls, shot))


def pack_sounds(sounds: list[Event]) -> bytes:
    """The sounds section: per sound, varint microseconds since the previous one, kind,
    the two ball ids (255: none), target (255: none), speed in mm/s (u16)."""
    out = bytearray()
    prev = 0
    for event in sounds:
        at = max(prev, round(event.time / TIME_UNIT))
        _put_varint(out, at - prev)
        prev = at
        ids = [*event.ids, NO_BALL]
        target = event.target if 0 <= event.target < NO_BALL else NO_BALL
        speed = min(65535, max(0, round(event.speed * 1000)))
        out += struct.pack("<BBBBH", SOUND_CODES[event.kind], ids[0], ids[1], target, speed)
    return bytes(out)


def _put_varint(out: bytearray, value: int) -> None:
    while value >= 128:
        out.append((value & 127) | 128)
        value >>= 7
    out.append(value)


def motion_bytes(
    shot_id: int,
    duration: float,
    tracks: bytes,
    balls: int,
    sounds: list[Event],
    version: int = MOTION_VERSION,
) -> bytes:
    """The whole binary `motion` message, `seq` 0 (`with_seq` sets it per broadcast)."""
    head = HEADER.pack(
        MOTION_KIND,
        version,
        0,
        shot_id,
        round(duration / TIME_UNIT),
        balls,
        len(sounds),
    )
    return head + tracks + pack_sounds(sounds)


def with_seq(message: bytes, seq: int) -> bytes:
    """The message with its room sequence number (bytes 2..5)."""
    return message[:SEQ_OFFSET] + struct.pack("<I", seq) + message[SEQ_OFFSET + 4 :]


SOUND_KINDS = tuple(SOUND_CODES)


def decode_motion(message: bytes) -> dict[str, Any]:
    """The binary `motion` message as plain values (tests, benchmarks, outside clients in
    Python): `type`, `seq`, `shot`, `duration` (s), `tracks` (per ball: `id`, `pocket`,
    knot `t` (s), `x`, `y` (m) and `phase` (rad rolled, from the first knot's angle); in
    version 2 also `z` (m) and `off_table`) and `sounds` (`t`, `kind`, `ids`, `speed`,
    `target`, as the engine's events)."""
    kind, version, seq, shot, duration, balls, count = HEADER.unpack_from(message)
    if kind != MOTION_KIND or version not in (MOTION_VERSION, MOTION_VERSION_HEIGHTS):
        raise ValueError(f"not a motion message of version {MOTION_VERSION} or 2")
    with_z = version == MOTION_VERSION_HEIGHTS
    at = HEADER.size
    tracks = []
    for _ in range(balls):
        ball, pocket, knots = struct.unpack_from("<BBH", message, at)
        at += 4
        t, at = _get_varint(message, at)
        x, y, phase = struct.unpack_from("<hhH", message, at)
        at += 6
        zs = [0]
        if with_z:
            (zs[0],) = struct.unpack_from("<H", message, at)
            at += 2
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
            if with_z:
                dz, at = _get_zigzag(message, at)
                zs.append(zs[-1] + dz)
        track: dict[str, Any] = {
            "id": ball,
            "pocket": None if pocket in (NO_BALL, OFF_TABLE_POCKET) else pocket,
            "t": [v / 1e6 for v in ts],
            "x": [v / 1e4 for v in xs],
            "y": [v / 1e4 for v in ys],
            "phase": [v * 2 * math.pi / PHASE_STEPS for v in phases],
        }
        if with_z:
            track["z"] = [v / 1e4 for v in zs]
            track["off_table"] = pocket == OFF_TABLE_POCKET
        tracks.append(track)
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
