"""Play now in one process: the queue (`server.players.MatchPool`), the rooms it opens, and
what each waiting player is told through the long-poll.

Everything that changes the queue runs synchronously on the event loop (join, leave, a
wave of pairing, opening the room and seating both players), so pairing is atomic: two
players pressing Play now at once cannot both be paired with a third, nor one twice.
Cluster mode has its own queue in Redis (`ClusterMatchmaker`), which opens the rooms of the
pairs it drains with this one.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging
from typing import Any

from server.players import MatchPool, Pairing, Waiting, Window, nearest_level, seat_token
from server.rooms import ActionError, LiveRoom, RoomRegistry

from .player_data import RankedRoom
from .playnow import (
    ASSIGNMENT_KEPT,
    Assignment,
    PlayNow,
    match_over,
    matched,
    seat_alone,
    waiting,
)
from .results import RankedResults

log = logging.getLogger(__name__)
WAVE_EVERY = 1.0  # s between two waves of pairing with the widened windows


class Matchmaker(PlayNow):
    def __init__(self, registry: RoomRegistry, results: RankedResults, window: Window) -> None:
        self.registry = registry
        self.results = results
        self.data = results.data
        self.pool = MatchPool(window)
        self.assignments: dict[str, Assignment] = {}
        self._waiters: dict[str, asyncio.Event] = {}
        self._told: set[str] = set()  # players shown their computer offer

    @property
    def clock(self) -> float:
        return self.registry.clock.monotonic()

    # ---- the queue ---------------------------------------------------------------------

    def join(self, entry: Waiting) -> Assignment | None:
        """Queue the player (pairing at once if someone suits); their assignment if paired.
        Raises `ActionError` when the server cannot open the room (the other player stays
        in the queue)."""
        self.assignments.pop(entry.player_id, None)
        self._told.discard(entry.player_id)
        pairing = self.pool.join(entry)
        if pairing is not None:
            try:
                self.open_room(pairing)
            except ActionError:
                other = pairing.first if pairing.second is entry else pairing.second
                self.pool.put_back(other)
                raise
        return self.assignments.get(entry.player_id)

    def leave(self, player_id: str) -> bool:
        self._told.discard(player_id)
        left = self.pool.leave(player_id) is not None
        self._wake(player_id)
        return left

    def wave(self) -> int:
        """Pair whoever the widened windows allow now, and wake those newly offered the
        computer. Returns the rooms opened."""
        now = self.clock
        opened = 0
        for pairing in self.pool.pair(now):
            try:
                self.open_room(pairing)
                opened += 1
            except ActionError as exc:
                log.warning("play now: no room for a pair (%s); both wait on", exc.code)
                self.pool.put_back(pairing.first)
                self.pool.put_back(pairing.second)
        for player_id in list(self._waiters):
            if player_id not in self._told and self.pool.offered_computer(player_id, now):
                self._wake(player_id)
        stale = [p for p, a in self.assignments.items() if now - a.at > ASSIGNMENT_KEPT]
        for player_id in stale:
            del self.assignments[player_id]
        return opened

    async def queued(self) -> set[str]:
        return self.pool.waiting_ids() | set(self.assignments)

    async def resume(self) -> int:
        """After the saved rooms are restored: watch the ranked ones again."""
        return self.results.restore(await self.data.open_ranked())

    async def run(self) -> None:
        while True:
            await asyncio.sleep(WAVE_EVERY)
            self.wave()

    # ---- `PlayNow`: the interface the routes use -----------------------------------------

    def now(self) -> float:
        """The time a queue entry's `since` is read on."""
        return self.clock

    async def enqueue(self, entry: Waiting) -> None:
        self.join(entry)

    async def dequeue(self, player_id: str) -> None:
        self.leave(player_id)

    async def status(self, player_id: str) -> dict[str, Any]:
        """What `GET /api/playnow` answers (`room` without its `url`)."""
        assignment = self.assignments.get(player_id)
        if assignment is not None and match_over(self.registry, assignment, gone_is_over=True):
            del self.assignments[player_id]
            assignment = None
        if assignment is not None:
            return matched(assignment)
        entry = self.pool.get(player_id)
        if entry is None:
            return {"status": "idle"}
        computer = self.computer_offer(player_id)
        if computer is not None:
            self.told(player_id)
        return waiting(entry, self.clock, self.pool.window, computer)

    async def take_computer(self, player_id: str, key: str) -> tuple[Assignment, str]:
        """Leave the queue for a room against the computer at the offered level (a friendly
        game: the computer's games are not rated)."""
        live, level, name = self.computer_room(player_id)
        assignment = seat_alone(live, player_id, name, key, self.data, self.clock)
        self.assignments[player_id] = assignment
        return assignment, level

    # ---- what a player sees ------------------------------------------------------------

    def computer_offer(self, player_id: str) -> str | None:
        """The computer's level offered to a player alone for long enough, else None."""
        entry = self.pool.get(player_id)
        if entry is None or not self.pool.offered_computer(player_id, self.clock):
            return None
        return nearest_level(entry.rating)

    def told(self, player_id: str) -> None:
        """The player has been shown their computer offer: a long-poll waits on from now."""
        self._told.add(player_id)

    async def wait(self, player_id: str, timeout: float) -> None:
        """Until the player's state changes (paired, offered the computer, left) or
        `timeout` seconds pass."""
        if timeout <= 0 or player_id in self.assignments or self.pool.get(player_id) is None:
            return
        if self.computer_offer(player_id) is not None and player_id not in self._told:
            return  # news: the offer
        event = self._waiters.setdefault(player_id, asyncio.Event())
        with contextlib.suppress(TimeoutError):
            await asyncio.wait_for(event.wait(), timeout)

    def _wake(self, player_id: str) -> None:
        event = self._waiters.pop(player_id, None)
        if event is not None:
            event.set()

    def computer_room(self, player_id: str) -> tuple[LiveRoom, str, str]:
        """Take the player out of the queue into a new private room with the computer at
        the offered level; returns the room, the level and the player's name."""
        level = self.computer_offer(player_id)
        if level is None:
            raise ActionError("not_offered", "The computer is offered after a while alone.")
        entry = self.pool.get(player_id)
        assert entry is not None
        live = self.registry.create(
            entry.kind, self.registry.settings.playnow_race_to, listed=False, opponent=level
        )
        self.leave(player_id)
        return live, level, entry.name

    # ---- rooms ---------------------------------------------------------------------------

    def open_room(self, pairing: Pairing) -> None:
        """A new listed room with both players seated (the first breaks), ranked."""
        settings = self.registry.settings
        live = self.registry.create(pairing.kind, settings.playnow_race_to, listed=True)
        room = live.room
        now = self.clock
        seated: list[tuple[Waiting, int, str]] = []
        for entry in (pairing.first, pairing.second):
            seat, token = room.join(entry.name, token=seat_token(entry.seat_key, room.room_id))
            seated.append((entry, seat, token))
        ranked = RankedRoom(
            room.room_id,
            pairing.kind,
            (pairing.first.player_id, pairing.second.player_id),
            (pairing.first.name, pairing.second.name),
        )
        wall = self.registry.clock.wall()
        self.results.start(live, ranked, wall)
        for entry, seat, _ in seated:
            self.data.player_seated(entry.player_id, room.room_id, seat, wall)
        for _ in seated:
            live.on_joined()
        for (entry, seat, token), (other, _, _) in zip(seated, reversed(seated), strict=True):
            self.assignments[entry.player_id] = Assignment(
                room.room_id, seat, token, pairing.kind, other.name, True, now
            )
            self._told.discard(entry.player_id)
            self._wake(entry.player_id)
