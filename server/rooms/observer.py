"""Where storage hooks in: a room tells its observer after every shot and change.

The default does nothing. A store implements these methods; they run on the event loop,
so they must be quick (queue the write and return). `shot_started` may return the queued
write's future: the shot's motion is shown only once it is done (a shot shown is a shot
kept: whoever plays the room next replays it from that stored start).
"""

from __future__ import annotations

from concurrent.futures import Future
from typing import TYPE_CHECKING, Any, Protocol

from server.engine import BallSet, Shot
from server.protocol import ShotPlan
from server.rules import Outcome

if TYPE_CHECKING:
    from .room import Room


class RoomObserver(Protocol):
    def shot_started(self, room: Room, seat: int, shot: Shot, shot_id: int) -> Future[Any] | None:
        """A shot was struck (the match is still as before it): save what a restart replays.
        Returns the save's future (the motion waits for it), or None (nothing to wait for)."""

    def shot_played(
        self, room: Room, seat: int, shot: Shot, before: BallSet, outcome: Outcome, plan: ShotPlan
    ) -> None:
        """A shot was simulated and judged: `before` is the table it was played from,
        `plan` the motion every member is shown."""

    def outcome(self, room: Room, cause: str, outcome: Outcome) -> None:
        """A non-shot outcome: "timeout", "concede" or "forfeit"."""

    def room_changed(self, room: Room) -> None:
        """Seats, match or score changed (join, rack, rematch); save the room."""

    def room_closed(self, room: Room) -> None:
        """The room expired and is gone."""

    def room_restored(self, room: Room, match_id: int | None) -> None:
        """A saved room came back after a restart, still recording into `match_id`."""

    def room_unreadable(self, room_id: str) -> None:
        """A saved room could not be read back (and will not be restored)."""


class NullObserver:
    def shot_started(
        self,
        room: Room,  # noqa: ARG002 (the protocol's signature)
        seat: int,  # noqa: ARG002
        shot: Shot,  # noqa: ARG002
        shot_id: int,  # noqa: ARG002
    ) -> Future[Any] | None:
        return None  # nothing stored, nothing to wait for

    def shot_played(
        self, room: Room, seat: int, shot: Shot, before: BallSet, outcome: Outcome, plan: ShotPlan
    ) -> None:
        pass

    def outcome(self, room: Room, cause: str, outcome: Outcome) -> None:
        pass

    def room_changed(self, room: Room) -> None:
        pass

    def room_closed(self, room: Room) -> None:
        pass

    def room_restored(self, room: Room, match_id: int | None) -> None:
        pass

    def room_unreadable(self, room_id: str) -> None:
        pass
