"""Play now's one interface, `PlayNow`, which both queues implement: `Matchmaker` (in this
process) and `ClusterMatchmaker` (in Redis, cluster mode); the app picks one. Also what a
queued player is told (`matched`, `waiting`) and the seat both give a player."""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass
from typing import Any

from server.players import Waiting, Window, seat_token
from server.rooms import LiveRoom, RoomRegistry

from .player_data import PlayerData

ASSIGNMENT_KEPT = 600.0  # s a matched player can still read where to go (at most)


@dataclass(frozen=True)
class Assignment:
    """Where a matched player plays: their seat and its token, shown to them only."""

    room_id: str
    seat: int
    token: str
    game: str
    opponent: str
    ranked: bool
    at: float  # the queue's time (`PlayNow.now`) it was made


class PlayNow(ABC):
    """The Play now queue as the routes use it."""

    @abstractmethod
    def now(self) -> float:
        """The time a queue entry's `since` is read on."""

    @abstractmethod
    async def enqueue(self, entry: Waiting) -> None:
        """Queue the player (one entry a player), pairing at once if someone suits. Raises
        `ActionError` when the room for a pair cannot be opened."""

    @abstractmethod
    async def dequeue(self, player_id: str) -> None:
        """Leave the queue (nothing happens if not in it)."""

    @abstractmethod
    async def status(self, player_id: str) -> dict[str, Any]:
        """What `GET /api/playnow` answers: `matched`, `waiting` or `idle`."""

    @abstractmethod
    async def wait(self, player_id: str, timeout: float) -> None:
        """Until the player's state changes (paired, offered the computer, left) or
        `timeout` seconds pass."""

    @abstractmethod
    async def take_computer(self, player_id: str, key: str) -> tuple[Assignment, str]:
        """Leave the queue for a private room against the computer at the offered level
        (not rated); the seat and the level. `ActionError("not_offered")` before then."""

    @abstractmethod
    async def queued(self) -> set[str]:
        """The players waiting in the queue or just paired (kept from guest pruning: their
        seats are about to be stored)."""

    @abstractmethod
    async def resume(self) -> int:
        """After the saved rooms are restored: watch the ranked ones again (their count)."""

    @abstractmethod
    async def run(self) -> None:
        """Pair in waves for ever (the lifespan's background task)."""


def matched(a: Assignment) -> dict[str, Any]:
    return {
        "status": "matched",
        "game": a.game,
        "room": {
            "room_id": a.room_id,
            "seat": a.seat,
            "token": a.token,
            "url": f"/r/{a.room_id}",
            "opponent": a.opponent,
            "ranked": a.ranked,
        },
    }


def waiting(entry: Waiting, now: float, window: Window, computer: str | None) -> dict[str, Any]:
    waited = max(0.0, now - entry.since)
    return {
        "status": "waiting",
        "game": entry.kind,
        "rating": round(entry.rating, 2),
        "waited": round(waited, 3),
        "window": round(window.at(waited), 2),
        "computer": computer,
    }


def seat_alone(
    live: LiveRoom, player_id: str, name: str, key: str, data: PlayerData, now: float
) -> Assignment:
    """Seat the player (with their own token) in a room the computer plays in."""
    room = live.room
    seat, token = room.join(name, token=seat_token(key, room.room_id))
    live.on_joined()
    data.player_seated(player_id, room.room_id, seat, live.clock.wall())
    return Assignment(room.room_id, seat, token, room.game, room.name_of(1 - seat), False, now)


def match_over(registry: RoomRegistry, assignment: Assignment, gone_is_over: bool) -> bool:
    """The assignment's match is over, or its room closed (`gone_is_over`: one process,
    where a room not in the registry is closed; in a cluster it may be another process's):
    a "matched" answer never outlives its match, so the lobby stays the lobby afterwards."""
    live = registry.get(assignment.room_id)
    if live is None:
        return gone_is_over
    return live.room.status == "finished"
