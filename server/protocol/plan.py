"""Turn a simulated shot into the timed messages a room streams (pure, no I/O).

Frames go out every `frame_every` ticks (plus the last tick) with integer millimetres;
events go out at their time, before the frame of the tick they fall in, those within one
frame message's span of each other in one message (`also`). `rest` events are left out:
clients make sounds from the others.
"""

from __future__ import annotations

import json
import math
from collections.abc import Iterator
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from server.engine import Event, ShotResult

from .frame_codec import encode_frames

SOUND_KINDS = frozenset(("strike", "ball", "cushion", "jaw", "pocket"))
ALWAYS_SENT = frozenset(("strike", "pocket"))
MAX_SOUNDS_PER_TICK = 12  # a rack's contacts can come by the thousand in one tick
SOUND_GAP = 0.05  # s: the same contact again within this is one sound

BallRow = tuple[int, int, int, int]  # id, x_mm, y_mm, cel


def message_text(kind: str, seq: int, body: str) -> str:
    """A message from its pre-encoded `body` (JSON without `type` and `seq`): string
    formatting only, so a room adds the sequence number without encoding again."""
    if len(body) > 2:
        return f'{{"type":"{kind}","seq":{seq},{body[1:]}'
    return f'{{"type":"{kind}","seq":{seq}}}'


class Timed(NamedTuple):
    """One message of the stream, `at` seconds after the strike. (A named tuple: a shot
    makes dozens of these on the event loop, and a frozen dataclass is slow to build.)"""

    at: float
    kind: str  # "frame" or "event"
    body: str  # the JSON without `type` and `seq`, which the room adds on sending
    droppable: bool
    tick: int = 0
    frame: int | None = None  # for frames: the index in the plan's `StreamFrames`

    @property
    def payload(self) -> dict:
        return {"type": self.kind, **json.loads(self.body)}


def frame_rows(
    ids: np.ndarray, positions: np.ndarray, cels: np.ndarray, on_table: np.ndarray
) -> list[BallRow]:
    """[id, x_mm, y_mm, cel] for every ball on the table."""
    mm = np.rint(positions * 1000.0).astype(np.int64)
    rows = zip(
        ids.tolist(),
        mm[:, 0].tolist(),
        mm[:, 1].tolist(),
        cels.tolist(),
        on_table.tolist(),
        strict=True,
    )
    return [(i, x, y, c) for i, x, y, c, on in rows if on]


@dataclass(frozen=True)
class StreamFrames:
    """The frames a shot streams, in integer millimetres, as arrays: the rows a member
    joining mid-shot is shown are built only when someone joins."""

    ids: np.ndarray  # (N,)
    ticks: np.ndarray  # (F,) the tick each frame shows
    mm: np.ndarray  # (F, N, 2) int64
    cels: np.ndarray  # (F, N)
    on_table: np.ndarray  # (F, N) bool

    def __len__(self) -> int:
        return len(self.ticks)

    def rows(self, j: int) -> list[BallRow]:
        rows = zip(
            self.ids.tolist(),
            self.mm[j, :, 0].tolist(),
            self.mm[j, :, 1].tolist(),
            self.cels[j].tolist(),
            self.on_table[j].tolist(),
            strict=True,
        )
        return [(i, x, y, c) for i, x, y, c, on in rows if on]


@dataclass(frozen=True)
class ShotPlan:
    """Everything a room streams for one shot, encoded once, in sending order."""

    frames: StreamFrames
    messages: list[Timed]

    def __iter__(self) -> Iterator[Timed]:
        return iter(self.messages)

    def __len__(self) -> int:
        return len(self.messages)


def stream_frames(result: ShotResult, frame_every: int) -> StreamFrames:
    """Every `frame_every`-th tick and the last one (tick 0: the table at rest, when a shot
    has no tick at all)."""
    frames = result.frames
    count = len(frames)
    ticks = list(range(frame_every, count + 1, frame_every))
    if count % frame_every or count == 0:
        ticks.append(count)
    if count == 0:
        final = result.final
        return StreamFrames(
            result.ids,
            np.array(ticks, dtype=np.int64),
            np.rint(final.positions * 1000.0).astype(np.int64)[None],
            np.zeros((1, len(result.ids)), dtype=np.int64),
            final.on_table.copy()[None],
        )
    index = np.array(ticks, dtype=np.int64) - 1
    return StreamFrames(
        result.ids,
        index + 1,
        np.rint(frames.positions[index] * 1000.0).astype(np.int64),
        frames.cels[index].astype(np.int64),
        frames.on_table[index],
    )


def plan_shot(
    result: ShotResult, shot_id: int, frame_every: int, frames_per_message: int = 1
) -> ShotPlan:
    """Every frame and event message of a shot, encoded, in sending order.

    With `frames_per_message` m > 1 a `frame` message goes out every m-th frame and carries
    the next m-1 frames early in `ahead` (the client plays them at their own ticks): the
    same positions at 1/m of the messages, which is what a server pays for per client.
    The last frame always goes alone, at its time."""
    if frames_per_message < 1:
        raise ValueError("frames_per_message must be at least 1")
    tick = result.frames.tick
    frames = stream_frames(result, frame_every)
    last = len(frames) - 1
    bodies = encode_frames(
        shot_id, frames.ticks, frames.ids, frames.mm, frames.cels, frames.on_table, last
    )
    ticks = frames.ticks.tolist()
    items: list[tuple[float, int, Timed]] = []
    for j in [*range(0, last, frames_per_message), last]:
        body = bodies[j]
        ahead = range(j + 1, min(j + frames_per_message, last))
        if ahead:
            rest = ",".join("{" + bodies[i][bodies[i].index('"tick"') :] for i in ahead)
            body = f'{body[:-1]},"ahead":[{rest}]}}'
        at = ticks[j] * tick
        items.append((at, 1, Timed(at, "frame", body, j != last, tick=ticks[j], frame=j)))
    window = frame_every * frames_per_message * tick  # the span of one frame message
    for group in _grouped(_sounds(result.events, tick), window):
        (event_tick, event), later = group[0], group[1:]
        body = event_body(shot_id, event_tick, event)
        if later:
            also = ",".join("{" + _without_shot(event_body(shot_id, t, e)) for t, e in later)
            body = f'{body[:-1]},"also":[{also}]}}'
        items.append((event.time, 0, Timed(event.time, "event", body, False, tick=event_tick)))
    items.sort(key=lambda item: (item[0], item[1]))
    return ShotPlan(frames, [timed for _, _, timed in items])


def event_body(shot_id: int, event_tick: int, event: Event) -> str:
    """The JSON of an `event` message without `type` and `seq`: what `server.codec.encode` gives for
    {"shot", "tick", "t", "kind", "ids", "speed", "target"}, by string formatting (a shot
    has dozens; json.dumps was a fifth of planning it)."""
    t, speed = round(event.time, 4), round(event.speed, 3)
    if not (math.isfinite(t) and math.isfinite(speed)):
        raise ValueError("an event time or speed is not finite")
    ids = ",".join(str(int(i)) for i in event.ids)
    return (
        f'{{"shot":{int(shot_id)},"tick":{int(event_tick)},"t":{t!r},'
        f'"kind":{json.dumps(event.kind)},"ids":[{ids}],"speed":{speed!r},'
        f'"target":{int(event.target)}}}'
    )


def _without_shot(body: str) -> str:
    return body[body.index('"tick"') :]


def _grouped(sounds: list[tuple[int, Event]], window: float) -> list[list[tuple[int, Event]]]:
    """Sounds in runs that start within `window` seconds of a run's first one: each run is
    one `event` message (the first event, the others in `also`), sent at the first one's
    time. A break's contacts came as dozens of messages a second per member, more than its
    frame messages; the client plays each sound at its own `t` anyway."""
    runs: list[list[tuple[int, Event]]] = []
    for item in sounds:
        if runs and item[1].time < runs[-1][0][1].time + window:
            runs[-1].append(item)
        else:
            runs.append([item])
    return runs


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
    kept: list[tuple[int, Event]] = []
    for event_tick, items in by_tick.items():
        items.sort(key=lambda e: (e.kind not in ALWAYS_SENT, -e.speed))
        kept.extend(
            (event_tick, e)
            for i, e in enumerate(items)
            if i < MAX_SOUNDS_PER_TICK or e.kind in ALWAYS_SENT
        )
    kept.sort(key=lambda item: item[1].time)
    return kept


def motion_text(plan: ShotPlan) -> str:
    """The messages a shot streamed, one a line (`at kind body`): what is stored to replay
    exactly what was shown, whatever engine runs the replay."""
    return "".join(f"{timed.at!r} {timed.kind} {timed.body}\n" for timed in plan.messages)


def motion_messages(text: str) -> list[tuple[float, str, str]]:
    """The inverse of `motion_text`: (at, kind, body) in sending order."""
    out = []
    for line in text.splitlines():
        at, kind, body = line.split(" ", 2)
        out.append((float(at), kind, body))
    return out
