"""The `frame` messages of a whole shot, encoded to JSON in one compiled pass.

Why compiled: a shot streams up to a few hundred frames of sixteen balls; building each
row list and `json.dumps` in Python took about as long as simulating the shot, holding the
GIL the event loop needs (see docs/performance.md). The bytes are exactly what
`json.dumps(payload, separators=(",", ":"))` gives for
`{"shot": S, "tick": K, "b": [[id, x_mm, y_mm, cel], ...]}` (plus `"last": true`).
"""

from __future__ import annotations

import numpy as np
from numba import njit

_SHOT = np.frombuffer(b'{"shot":', dtype=np.uint8)
_TICK = np.frombuffer(b',"tick":', dtype=np.uint8)
_BALLS = np.frombuffer(b',"b":[', dtype=np.uint8)
_LAST = np.frombuffer(b'],"last":true}', dtype=np.uint8)
_END = np.frombuffer(b"]}", dtype=np.uint8)
_MAX_INT_CHARS = 20  # "-9223372036854775808"
_INT64_MIN = -(2**63)
_INT64_MIN_TEXT = np.frombuffer(b"-9223372036854775808", dtype=np.uint8)


@njit(cache=True)
def _put(buf: np.ndarray, pos: int, text: np.ndarray) -> int:
    for i in range(len(text)):
        buf[pos + i] = text[i]
    return pos + len(text)


@njit(cache=True)
def _put_int(buf: np.ndarray, pos: int, value: int) -> int:
    if value == _INT64_MIN:  # has no positive counterpart
        return _put(buf, pos, _INT64_MIN_TEXT)
    if value < 0:
        buf[pos] = 45  # "-"
        pos += 1
        value = -value
    digits = 1
    rest = value // 10
    while rest > 0:
        digits += 1
        rest //= 10
    for k in range(digits - 1, -1, -1):
        buf[pos + k] = 48 + value % 10
        value //= 10
    return pos + digits


@njit(cache=True, nogil=True)
def _encode(
    shot_id: int,
    ticks: np.ndarray,
    ids: np.ndarray,
    mm: np.ndarray,
    cels: np.ndarray,
    on_table: np.ndarray,
    last: int,
    shot_text: np.ndarray,
    tick_text: np.ndarray,
    balls_text: np.ndarray,
    last_text: np.ndarray,
    end_text: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    count, n = on_table.shape
    per_frame = 64 + n * (4 * _MAX_INT_CHARS + 8)
    buf = np.empty(count * per_frame, dtype=np.uint8)
    offsets = np.empty(count + 1, dtype=np.int64)
    pos = 0
    for j in range(count):
        offsets[j] = pos
        pos = _put(buf, pos, shot_text)
        pos = _put_int(buf, pos, shot_id)
        pos = _put(buf, pos, tick_text)
        pos = _put_int(buf, pos, ticks[j])
        pos = _put(buf, pos, balls_text)
        first = True
        for b in range(n):
            if not on_table[j, b]:
                continue
            if not first:
                buf[pos] = 44  # ","
                pos += 1
            first = False
            buf[pos] = 91  # "["
            pos = _put_int(buf, pos + 1, ids[b])
            buf[pos] = 44
            pos = _put_int(buf, pos + 1, mm[j, b, 0])
            buf[pos] = 44
            pos = _put_int(buf, pos + 1, mm[j, b, 1])
            buf[pos] = 44
            pos = _put_int(buf, pos + 1, cels[j, b])
            buf[pos] = 93  # "]"
            pos += 1
        pos = _put(buf, pos, last_text if j == last else end_text)
    offsets[count] = pos
    return buf[:pos], offsets


def encode_frames(
    shot_id: int,
    ticks: np.ndarray,
    ids: np.ndarray,
    mm: np.ndarray,
    cels: np.ndarray,
    on_table: np.ndarray,
    last: int,
) -> list[str]:
    """One JSON object (without `type` and `seq`) per frame; frame `last` says so."""
    buf, offsets = _encode(
        int(shot_id),
        np.ascontiguousarray(ticks, dtype=np.int64),
        np.ascontiguousarray(ids, dtype=np.int64),
        np.ascontiguousarray(mm, dtype=np.int64),
        np.ascontiguousarray(cels, dtype=np.int64),
        np.ascontiguousarray(on_table, dtype=np.bool_),
        int(last),
        _SHOT,
        _TICK,
        _BALLS,
        _LAST,
        _END,
    )
    text = buf.tobytes().decode("ascii")
    bounds = offsets.tolist()
    return [text[bounds[j] : bounds[j + 1]] for j in range(len(bounds) - 1)]
