"""Where storage hooks in (issue 7): a room tells its observer after every shot and change.

The default does nothing. A store implements these methods; they run on the event loop,
so they must be quick (queue the write and return).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Protocol

from server.engine import BallSet, Shot
from server.rules import Outcome

if TYPE_CHECKING:
    from .room import Room


class RoomObserver(Protocol):
    def shot_started(self, room: Room, seat: int, shot: Shot, shot_id: int) -> None:
        """A shot was struck (the match is still as before it): save what a restart replays."""

    def shot_played(self, room: Room, seat: int, shot: Shot, before: BallSet,
                    outcome: Outcome) -> None:
        """A shot was simulated and judged: `before` is the table it was played from."""

    def outcome(self, room: Room, cause: str, outcome: Outcome) -> None:
        """A non-shot outcome: "timeout", "concede" or "forfeit"."""

    def room_changed(self, room: Room) -> None:
        """Seats, match or score changed (join, rack, rematch); save the room."""

    def room_closed(self, room: Room) -> None:
        """The room expired and is gone."""


class NullObserver:
    def shot_started(self, room: Room, seat: int, shot: Shot, shot_id: int) -> None:
        pass

    def shot_played(self, room: Room, seat: int, shot: Shot, before: BallSet,
                    outcome: Outcome) -> None:
        pass

    def outcome(self, room: Room, cause: str, outcome: Outcome) -> None:
        pass

    def room_changed(self, room: Room) -> None:
        pass

    def room_closed(self, room: Room) -> None:
        pass
