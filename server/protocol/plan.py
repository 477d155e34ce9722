"""What a room sends for one shot (pure, no I/O): the binary `motion` message.

The whole shot is simulated before anyone sees it, so its motion goes out at once, at the
strike: every ball's exact track (traced by the engine, packed by `protocol.motion`) and
its sounds. Clients play it on their own clock. The room keeps the shot's frames every
`frame_every` ticks (integer millimetres) only for the `state` of a member who joins while
the balls roll. `rest` events make no sound and are not sent.
"""

from __future__ import annotations

import base64
import json
import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from server.engine import BALL_RADIUS, TICK_HZ, Event, ShotResult

from .motion import Tracks, motion_bytes, pack_tracks

SOUND_KINDS = frozenset(("strike", "ball", "cushion", "jaw", "pocket", "land"))
ALWAYS_SENT = frozenset(("strike", "pocket"))
MAX_SOUNDS_PER_TICK = 12  # a rack's contacts can come by the thousand in one tick
SOUND_GAP = 0.05  # s: the same contact again within this is one sound
CELS = 16  # sprite cels per turn

BallRow = tuple[int, int, int, int]  # id, x_mm, y_mm, cel


class Timed(NamedTuple):
    """A point of the shot being shown: the room remembers the frame a member joining now
    is shown (`Room.show`)."""

    tick: int  # the engine tick it shows
    frame: int  # its index in the plan's `StreamFrames`

    @property
    def at(self) -> float:
        """Seconds after the strike it is due."""
        return self.tick / TICK_HZ


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
    """Everything a room sends for one shot, encoded once: the binary `motion` message
    (sent whole at the strike, its `seq` set per broadcast), and the frames a member
    joining mid-shot is shown in `state.balls`."""

    shot_id: int
    frames: StreamFrames
    motion: bytes  # the `motion` message with seq 0
    duration: float  # s from the strike to the last tick
    sounds: int  # how many sounds it carries

    def shown_at(self, elapsed: float) -> Timed:
        """The frame of the stream `elapsed` seconds after the strike (the latest due)."""
        ticks = self.frames.ticks
        j = max(0, int(np.searchsorted(ticks, elapsed * TICK_HZ, side="right")) - 1)
        return Timed(int(ticks[j]), j)

    @property
    def last(self) -> Timed:
        j = len(self.frames) - 1
        return Timed(int(self.frames.ticks[j]), j)


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


def plan_shot(result: ShotResult, tracks: Tracks, shot_id: int, frame_every: int) -> ShotPlan:
    """The shot's `motion` message (its exact tracks and its sounds) and its frames.

    `tracks` must be the same shot traced (`protocol.motion.trace`): its ticks are the
    engine's, which is checked."""
    if tracks.ticks != len(result.frames):
        raise ValueError("the traced shot is not the simulated one")
    sounds = [event for _, event in _sounds(result.events, result.frames.tick)]
    duration = result.duration
    balls = int(np.count_nonzero(np.diff(tracks.offsets)))
    message = motion_bytes(shot_id, duration, tracks.packed, balls, sounds, tracks.version)
    return ShotPlan(shot_id, stream_frames(result, frame_every), message, duration, len(sounds))


def _sounds(events: list[Event], tick: float) -> list[tuple[int, Event]]:
    """The events worth a sound, with their tick. A contact (kind, balls, target) that
    repeats within SOUND_GAP of its last sound is the same sustained touch (a ball pressed by
    its spin against another collides again every few microseconds) and is not sent again;
    at most MAX_SOUNDS_PER_TICK a tick, the loudest (strikes and pockets always)."""
    last: dict[tuple[str, tuple[int, ...], int], float] = {}
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
    """What is stored to replay exactly what was shown, whatever engine runs the replay:
    one line, `0.0 motion <base64 of the motion message>` (older shots stored their
    `frame` and `event` messages, one a line: `at kind body`)."""
    return f"0.0 motion {base64.b64encode(plan.motion).decode('ascii')}\n"


def motion_messages(text: str) -> list[tuple[float, str, str]]:
    """The inverse of `motion_text` (and of the older form): (at, kind, body) in order."""
    out = []
    for line in text.splitlines():
        at, kind, body = line.split(" ", 2)
        out.append((float(at), kind, body))
    return out


def stored_motion(text: str, shot_id: int) -> bytes:
    """The `motion` message of a stored shot (`motion_text`). A shot stored before the
    `motion` message kept its `frame` and `event` messages: their frames (every 6th tick,
    millimetres, cels) become the knots of its tracks, their sounds its sounds."""
    lines = motion_messages(text)
    if len(lines) == 1 and lines[0][1] == "motion":
        return base64.b64decode(lines[0][2], validate=True)
    frames: dict[int, list[list[int]]] = {}
    sounds: list[Event] = []
    for _, kind, body in lines:
        message = json.loads(body)
        if kind == "frame":
            for frame in [message, *message.get("ahead", ())]:
                frames[frame["tick"]] = frame["b"]
        elif kind == "event":
            for e in [message, *message.get("also", ())]:
                sounds.append(Event(e["t"], e["kind"], tuple(e["ids"]), e["speed"], e["target"]))
    ticks = sorted(frames)
    ids = sorted({row[0] for rows in frames.values() for row in rows})
    column = {ball: i for i, ball in enumerate(ids)}
    count, n = len(ticks), len(ids)
    positions = np.zeros((count, n, 2))
    cels = np.zeros((count, n), dtype=np.int64)
    on = np.zeros((count, n), dtype=np.bool_)
    for j, tick in enumerate(ticks):
        for ball, x, y, cel in frames[tick]:
            positions[j, column[ball]] = (x / 1000.0, y / 1000.0)
            cels[j, column[ball]] = cel
            on[j, column[ball]] = True
    phases = _unwrapped(positions, cels, on)
    knots: list[int] = []
    offsets = [0]
    for b in range(n):
        knots.extend(np.flatnonzero(on[:, b]).tolist())
        offsets.append(len(knots))
    pockets = np.full(n, -1, dtype=np.int64)
    for sound in sounds:
        if sound.kind == "pocket" and sound.ids[0] in column:
            pockets[column[sound.ids[0]]] = sound.target
    packed = pack_tracks(
        np.array(ids, dtype=np.int64),
        pockets,
        np.array(ticks, dtype=np.float64) / TICK_HZ,
        positions,
        phases,
        np.array(knots, dtype=np.int64),
        np.array(offsets, dtype=np.int64),
        np.zeros(phases.shape),
        False,
    ).tobytes()
    sounds.sort(key=lambda e: e.time)
    duration = ticks[-1] / TICK_HZ if ticks else 0.0
    return motion_bytes(shot_id, duration, packed, n, sounds)


def _unwrapped(positions: np.ndarray, cels: np.ndarray, on: np.ndarray) -> np.ndarray:
    """Rolled angles from sprite cels (which wrap every turn): each step the number of cels
    nearest to the distance rolled (what the web client did with such frames)."""
    cel = 2 * math.pi / CELS
    phases = (cels + 0.5) * cel
    for j in range(1, len(cels)):
        rolled = np.hypot(*(positions[j] - positions[j - 1]).T) / (2 * math.pi * BALL_RADIUS)
        base = (cels[j] - cels[j - 1]) % CELS
        step = base + np.round((rolled * CELS - base) / CELS) * CELS
        phases[j] = np.where(on[j] & on[j - 1], phases[j - 1] + step * cel, phases[j])
    return phases
