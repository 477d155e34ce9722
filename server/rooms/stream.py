"""Turn a simulated shot into the timed messages a room streams (pure, no I/O).

Frames go out every `frame_every` ticks (plus the last tick) with integer millimetres;
events go out at their time, before the frame of the tick they fall in. `rest` events are
left out: clients make sounds from the others.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from server.engine import Event, ShotResult

SOUND_KINDS = frozenset(("strike", "ball", "cushion", "jaw", "pocket"))
ALWAYS_SENT = frozenset(("strike", "pocket"))
MAX_SOUNDS_PER_TICK = 12  # a rack's contacts can come by the thousand in one tick
SOUND_GAP = 0.05  # s: the same contact again within this is one sound

BallRow = tuple[int, int, int, int]  # id, x_mm, y_mm, cel


@dataclass(frozen=True)
class Timed:
    """One message of the stream, `at` seconds after the strike."""

    at: float
    payload: dict  # without `seq`, which the room assigns on sending
    droppable: bool
    balls: list[BallRow] | None = None  # for frames: the table shown from now on
    tick: int = 0


def frame_rows(ids: np.ndarray, positions: np.ndarray, cels: np.ndarray,
               on_table: np.ndarray) -> list[BallRow]:
    """[id, x_mm, y_mm, cel] for every ball on the table."""
    mm = np.rint(positions * 1000.0).astype(np.int64)
    rows = zip(ids.tolist(), mm[:, 0].tolist(), mm[:, 1].tolist(), cels.tolist(),
               on_table.tolist(), strict=True)
    return [(i, x, y, c) for i, x, y, c, on in rows if on]


def plan_shot(result: ShotResult, shot_id: int, frame_every: int) -> list[Timed]:
    """Every frame and event message of a shot, in sending order."""
    frames = result.frames
    tick = frames.tick
    count = len(frames)
    items: list[tuple[float, int, Timed]] = []
    for k in range(frame_every, count + 1, frame_every):
        items.append(_frame(result, shot_id, k, count))
    if count % frame_every or count == 0:
        items.append(_frame(result, shot_id, count, count))
    for event_tick, event in _sounds(result.events, tick):
        payload = {"type": "event", "shot": shot_id, "tick": int(event_tick),
                   "t": round(event.time, 4), "kind": event.kind, "ids": list(event.ids),
                   "speed": round(event.speed, 3), "target": event.target}
        items.append((event.time, 0, Timed(event.time, payload, False, tick=event_tick)))
    items.sort(key=lambda item: (item[0], item[1]))
    return [timed for _, _, timed in items]


def _sounds(events: list[Event], tick: float) -> list[tuple[int, Event]]:
    """The events worth a sound, with their tick. A contact (kind, balls, target) that
    repeats within SOUND_GAP of its last sound is the same sustained touch (a ball pressed by
    its spin against another collides again every few microseconds) and is not sent again;
    at most MAX_SOUNDS_PER_TICK a tick, the loudest (strikes and pockets always)."""
    last: dict[tuple, float] = {}
    by_tick: dict[int, list[Event]] = {}
    for event in events:
        if event.kind not in SOUND_KINDS:
            continue
        key = (event.kind, event.ids, event.target)
        if event.kind not in ALWAYS_SENT and key in last and event.time - last[key] < SOUND_GAP:
            continue
        last[key] = event.time
        by_tick.setdefault(max(0, math.ceil(event.time / tick - 1e-9)), []).append(event)
    kept = []
    for event_tick, items in by_tick.items():
        items.sort(key=lambda e: (e.kind not in ALWAYS_SENT, -e.speed))
        kept.extend((event_tick, e) for i, e in enumerate(items)
                    if i < MAX_SOUNDS_PER_TICK or e.kind in ALWAYS_SENT)
    kept.sort(key=lambda item: item[1].time)
    return kept


def _frame(result: ShotResult, shot_id: int, k: int, count: int) -> tuple[float, int, Timed]:
    frames = result.frames
    at = k * frames.tick
    if count == 0:  # nothing moved (cannot happen for a legal shot; keep the stream whole)
        rows = frame_rows(result.ids, result.final.positions, np.zeros(len(result.ids), int),
                          result.final.on_table)
    else:
        i = k - 1
        rows = frame_rows(result.ids, frames.positions[i], frames.cels[i], frames.on_table[i])
    payload: dict = {"type": "frame", "shot": shot_id, "tick": k, "b": rows}
    if k == count:
        payload["last"] = True
    return at, 1, Timed(at, payload, k != count, balls=rows, tick=k)
