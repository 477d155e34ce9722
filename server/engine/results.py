"""What a simulated shot produces: events in time order, per-tick frames, the final state."""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from enum import StrEnum
from functools import cached_property
from typing import overload

import numpy as np

from .balls import CUE, BallSet


class EventKind(StrEnum):
    STRIKE = "strike"  # the cue hits the cue ball
    BALL = "ball"  # two balls collide
    CUSHION = "cushion"  # a ball hits a cushion
    JAW = "jaw"  # a ball hits a pocket's point
    POCKET = "pocket"  # a ball drops
    REST = "rest"  # a ball stops translating


class FlightKind(StrEnum):
    """What only a flying ball does (a raised cue's jump or hop): kinds apart from
    `EventKind`, which lists what every shot can do."""

    LAND = "land"  # a flying ball meets the slate (and hops again, or stays down)
    OFF_TABLE = "off_table"  # a flying ball clears a cushion: out of play


# Kind codes used inside the compiled kernels: EventKind's in order, then FlightKind's.
EVENT_CODES: tuple[StrEnum, ...] = (*EventKind, *FlightKind)
_CODE_OF = {kind.value: code for code, kind in enumerate(EVENT_CODES)}
_KIND_NAMES = tuple(kind.value for kind in EVENT_CODES)


@dataclass(frozen=True)
class Event:
    """One thing that happened during a shot.

    time: seconds since the strike (or since the start of the tick for `step`).
    kind: one of "strike", "ball", "cushion", "jaw", "pocket", "rest", "land", "off_table".
    ids: the ball ids involved (two for "ball", one otherwise).
    speed: impact speed in m/s (relative normal speed for "ball", normal speed into the
        cushion or jaw, the ball's speed for "strike", "pocket" and "off_table", the speed
        down into the slate for "land", 0 for "rest").
    target: the cushion, jaw or pocket index (into `Table.cushions`, `Table.jaws`,
        `Table.pockets`) for those kinds (for "off_table" the cushion, or the jaw, it
        flew over), else -1.
    """

    time: float
    kind: str
    ids: tuple[int, ...]
    speed: float
    target: int = -1


@dataclass(frozen=True)
class Frame:
    """The table at the end of one tick: what the client draws.

    positions (N, 2) m, cels (N,) sprite cel index, on_table (N,) bool; rows follow
    `ShotResult.ids`. A pocketed ball's position is its pocket's centre.
    """

    tick: int
    time: float
    positions: np.ndarray
    cels: np.ndarray
    on_table: np.ndarray


class FrameSequence(Sequence[Frame]):
    """Frames stored as three stacked arrays; `Frame` views are made on access."""

    def __init__(
        self, tick: float, positions: np.ndarray, cels: np.ndarray, on_table: np.ndarray
    ) -> None:
        self.tick = tick
        self.positions = positions  # (T, N, 2)
        self.cels = cels  # (T, N)
        self.on_table = on_table  # (T, N)

    def __len__(self) -> int:
        return len(self.positions)

    @overload
    def __getitem__(self, index: int) -> Frame: ...
    @overload
    def __getitem__(self, index: slice) -> list[Frame]: ...

    def __getitem__(self, index: int | slice) -> Frame | list[Frame]:
        if isinstance(index, slice):
            return [self[i] for i in range(*index.indices(len(self)))]
        n = len(self)
        if index < 0:
            index += n
        if not 0 <= index < n:
            raise IndexError(index)
        return Frame(
            index + 1,
            (index + 1) * self.tick,
            self.positions[index],
            self.cels[index],
            self.on_table[index],
        )

    def __iter__(self) -> Iterator[Frame]:
        for i in range(len(self)):
            yield self[i]


@dataclass(frozen=True)
class ShotResult:
    """A shot simulated to rest: `frames` (one per tick), `events` (time order), `final`."""

    ids: np.ndarray
    frames: FrameSequence
    events: list[Event]
    final: BallSet
    stalled_ticks: int = 0  # ticks cut short by the per-tick event bound (never seen in play)

    @property
    def duration(self) -> float:
        return len(self.frames) * self.frames.tick

    def contacts(self) -> list[tuple[int, int, int, int]]:
        """Each event as (kind code, ball id, other ball id or -1, target): what a referee
        reads (`Settled.contacts` gives the same for the same shot)."""
        return [
            (_CODE_OF[e.kind], e.ids[0], e.ids[1] if len(e.ids) > 1 else -1, e.target)
            for e in self.events
        ]

    def first_contact(self, cue: int = 0) -> int | None:
        """Id of the first ball the cue ball (`cue`) touched, or None."""
        for e in self.events:
            if e.kind == EventKind.BALL and cue in e.ids:
                return next(i for i in e.ids if i != cue)
        return None

    def pocketed(self) -> list[int]:
        """Ids pocketed during the shot, in the order they dropped."""
        return [e.ids[0] for e in self.events if e.kind == EventKind.POCKET]


@dataclass(frozen=True)
class Settled:
    """A shot simulated to rest without its frames (`settle`): what happened (`events`) and
    where the balls stopped (`final`), as `ShotResult` has them, bit for bit. For callers
    that never draw the shot, such as the computer's search.

    The events are kept as the kernel's rows (`rows`: time, kind code, row of a ball, row
    of the other or -1, speed, target; the strike not among them) and made `Event`s only
    when asked for: a search reads most shots' `contacts()` alone, and making the events
    cost about 17 us a shot, some 6 % of its short shots."""

    rows: np.ndarray
    final: BallSet
    duration: float
    stalled_ticks: int = 0
    strike_speed: float = 0.0
    struck: int = CUE  # the ball the cue struck (`Shot.ball`)

    @cached_property
    def events(self) -> list[Event]:
        strike = Event(0.0, EventKind.STRIKE.value, (self.struck,), self.strike_speed)
        return [strike, *events_from(self.rows, self.final.ids)]

    def contacts(self) -> list[tuple[int, int, int, int]]:
        """`ShotResult.contacts`, read from the rows."""
        id_of = [*self.final.ids.tolist(), -1]  # a missing second ball's row -1 reads -1
        strike = (_CODE_OF[EventKind.STRIKE.value], self.struck, -1, -1)
        # Every column as ints in one conversion (the time and speed, truncated, unread).
        return [strike] + [
            (code, id_of[a], id_of[b], target)
            for _, code, a, b, _, target in self.rows.astype(np.int64).tolist()
        ]


def events_from(rows: np.ndarray, ids: np.ndarray) -> list[Event]:
    """`Event`s from the kernel's event rows. A sustained contact can log thousands of
    events in one shot, so this loop stays lean: the server runs it on its event loop."""
    names, id_of = _KIND_NAMES, ids.tolist()
    codes = rows[:, 1].astype(np.int64).tolist()
    first = rows[:, 2].astype(np.int64).tolist()
    second = rows[:, 3].astype(np.int64).tolist()
    targets = rows[:, 5].astype(np.int64).tolist()
    return [
        Event(time, names[code], (id_of[a],) if b < 0 else (id_of[a], id_of[b]), speed, target)
        for time, speed, code, a, b, target in zip(
            rows[:, 0].tolist(), rows[:, 4].tolist(), codes, first, second, targets, strict=True
        )
    ]
