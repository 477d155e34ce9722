"""The hook of a ranked room: an observer around the room's own (the recorder) that calls
`on_over` once, when the room's first match ends. Only that match counts: a rematch in the
same room is a friendly game."""

from __future__ import annotations

from collections.abc import Callable
from concurrent.futures import Future
from typing import TYPE_CHECKING, Any

from server.rooms import Room
from server.rooms.observer import RoomObserver

if TYPE_CHECKING:  # the observer's signatures only
    from server.engine import BallSet, Shot
    from server.protocol import ShotPlan
    from server.rules import Outcome


class RankedWatch:
    """Implements `RoomObserver`: passes everything on to `inner`, then checks the match."""

    def __init__(self, inner: RoomObserver, on_over: Callable[[Room], None]) -> None:
        self.inner = inner
        self.on_over = on_over
        self.done = False

    def _check(self, room: Room) -> None:
        match = room.match
        if self.done or match is None or not (match.over or room.abandoned):
            return
        self.done = True
        self.on_over(room)

    def shot_started(self, room: Room, seat: int, shot: Shot, shot_id: int) -> Future[Any] | None:
        return self.inner.shot_started(room, seat, shot, shot_id)

    def shot_played(
        self, room: Room, seat: int, shot: Shot, before: BallSet, outcome: Outcome, plan: ShotPlan
    ) -> None:
        self.inner.shot_played(room, seat, shot, before, outcome, plan)
        self._check(room)

    def outcome(self, room: Room, cause: str, outcome: Outcome) -> None:
        self.inner.outcome(room, cause, outcome)
        self._check(room)

    def room_changed(self, room: Room) -> None:
        self.inner.room_changed(room)
        self._check(room)

    def room_closed(self, room: Room) -> None:
        self.inner.room_closed(room)

    def room_restored(self, room: Room, match_id: int | None) -> None:
        self.inner.room_restored(room, match_id)

    def room_unreadable(self, room_id: str) -> None:
        self.inner.room_unreadable(room_id)
