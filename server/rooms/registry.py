"""All live rooms of this process, the sweeper that expires idle ones, and the watchdog
that drops members who stopped reading."""

from __future__ import annotations

import asyncio
import logging
from collections.abc import Callable
from typing import Any

from server.config import Settings
from server.store import RoomSnapshot

from .clock import SYSTEM_CLOCK, Clock, SeedSource
from .drills import DrillSetup
from .errors import ActionError
from .live import LiveRoom
from .metrics import StreamMetrics
from .observer import NullObserver, RoomObserver
from .room import Room
from .shot_runner import ShotRunner
from .snapshot import room_from_snapshot
from .tokens import new_room_id

log = logging.getLogger(__name__)
CLOSE_EXPIRED = 1001
STATS_MAX_AGE = 1.0  # s
STATS_CACHED_FROM = 100  # rooms


class RoomRegistry:
    """Creates, finds, lists and expires rooms. One process owns its rooms (one worker)."""

    def __init__(
        self,
        settings: Settings,
        observer: RoomObserver | None = None,
        clock: Clock = SYSTEM_CLOCK,
        seeds: SeedSource | None = None,
    ) -> None:
        self.settings = settings
        self.observer = observer
        self.clock = clock
        self.seeds = seeds or SeedSource()
        self.rooms: dict[str, LiveRoom] = {}
        self.owners: dict[str, str] = {}  # room id -> the client that opened it
        self._open_by: dict[str, int] = {}  # client -> rooms it has open
        self._listed: list[LiveRoom] | None = None  # listed rooms, newest first (cached)
        self._stats: dict[float, tuple[float, dict[str, Any]]] = {}  # window -> (loop time, stats)
        self.metrics = StreamMetrics()
        # Told when a room opens here, and when one closes here for good (cluster mode
        # registers it with the others, then clears its shared entries).
        self.on_create: Callable[[LiveRoom], None] | None = None
        self.on_forget: Callable[[str], None] | None = None
        self.runner = ShotRunner(settings.shot_workers, settings.frame_every)

    def create(
        self,
        game: str,
        race_to: int = 1,
        shot_clock: float | None = None,
        listed: bool = True,
        owner: str | None = None,
        opponent: str | None = None,
        setup: DrillSetup | None = None,
    ) -> LiveRoom:
        """A new room. `owner` (the client opening it) may hold `max_rooms_per_client`
        rooms at once, so no single client can fill the server; `listed=False` makes a
        private table, reached only through its link."""
        if len(self.rooms) >= self.settings.max_rooms:
            raise ActionError("too_many_rooms", "The server is full; try again later.")
        if owner is not None and self._open_by.get(owner, 0) >= self.settings.max_rooms_per_client:
            raise ActionError(
                "too_many_rooms_open",
                f"You have {self.settings.max_rooms_per_client} tables open; play or wait "
                "for one to close.",
            )
        room_id = new_room_id()
        while room_id in self.rooms:
            room_id = new_room_id()
        clock = self.settings.shot_clock if shot_clock is None else shot_clock
        room = Room(
            room_id,
            game,
            race_to=race_to,
            shot_clock=clock,
            seed=self.seeds.next(),
            created_at=self.clock.wall(),
            listed=listed,
            setup=setup,
        )
        if opponent is not None:  # the computer takes the second seat at once
            room.add_computer(opponent)
        live = self._live(room)
        self.rooms[room_id] = live
        self._listed = None
        if owner is not None:
            self.owners[room_id] = owner
            self._open_by[owner] = self._open_by.get(owner, 0) + 1
        if self.observer is not None:
            self.observer.room_changed(room)
        if self.on_create is not None:
            self.on_create(live)
        return live

    def restore(self, snapshots: list[RoomSnapshot]) -> list[LiveRoom]:
        """Bring saved rooms back after a restart: seats empty until their players
        reconnect with their tokens; a shot that was in flight is played again from its
        start (same result, bit for bit). Needs the running loop. A snapshot that cannot be
        read is logged and skipped."""
        restored = []
        for snap in snapshots:
            if snap.room_id in self.rooms:
                continue  # still live in this process
            try:
                saved = room_from_snapshot(snap.data)
            except (KeyError, TypeError, ValueError):
                log.exception("room %s could not be restored; dropped", snap.room_id)
                if self.observer is not None:
                    self.observer.room_unreadable(snap.room_id)
                continue
            live = self._live(saved.room)
            if self.observer is not None:
                self.observer.room_restored(saved.room, saved.match_id)
            self.rooms[saved.room.room_id] = live
            self._listed = None
            live.resume(saved.pending)
            restored.append(live)
        if restored:
            log.info("restored %d rooms", len(restored))
        return restored

    def _live(self, room: Room) -> LiveRoom:
        """`room` on the loop, with the shot runner and stream metrics all rooms share."""
        return LiveRoom(
            room,
            self.settings,
            self.observer,
            self.clock,
            runner=self.runner,
            metrics=self.metrics,
        )

    def get(self, room_id: str) -> LiveRoom | None:
        return self.rooms.get(room_id)

    def listing(self) -> list[LiveRoom]:
        """The listed rooms, newest first: sorted once per change of the room set, not
        once per request (a listing flood must not cost O(rooms log rooms) each time)."""
        if self._listed is None:
            listed = (live for live in self.rooms.values() if live.room.listed)
            self._listed = sorted(listed, key=lambda r: r.room.created_at, reverse=True)
        return self._listed

    def forget(self, room_id: str) -> LiveRoom | None:
        live = self.rooms.pop(room_id, None)
        self._listed = None
        owner = self.owners.pop(room_id, None)
        if owner is not None:
            left = self._open_by.get(owner, 1) - 1
            if left > 0:
                self._open_by[owner] = left
            else:
                self._open_by.pop(owner, None)
        if live is not None and self.on_forget is not None:
            self.on_forget(room_id)
        return live

    def release(self, room_id: str, code: int, reason: str) -> LiveRoom | None:
        """Stop playing a room that another process plays now (or will): its members are
        closed with `code`, and the store is not told it closed (it lives on elsewhere)."""
        live = self.rooms.get(room_id)
        if live is None:
            return None
        hook, self.on_forget = self.on_forget, None
        try:
            self.forget(room_id)
        finally:
            self.on_forget = hook
        live.observer = NullObserver()
        live.close(code, reason)
        return live

    def sweep(self, now: float | None = None) -> list[str]:
        """Close and forget rooms nobody has used for their time to live."""
        now = self.clock.monotonic() if now is None else now
        gone = [rid for rid, live in self.rooms.items() if live.is_idle(now)]
        for rid in gone:
            live = self.forget(rid)
            assert live is not None
            live.close(CLOSE_EXPIRED, "expired")
            log.info("room %s expired", rid)
        return gone

    async def run_sweeper(self) -> None:
        while True:
            await asyncio.sleep(self.settings.sweep_interval)
            self.sweep()

    def check_senders(self, now: float) -> int:
        """Drop every member whose outbox has been stuck past its deadline (loop time)."""
        return sum(
            conn.check_deadline(now)
            for live in list(self.rooms.values())
            for conn in list(live.members.values())
        )

    def stats(self, window: float) -> dict[str, Any]:
        """Rooms, members and the frame send lateness of the last `window` seconds. A walk
        over every room, so it is computed at most once a second per window: a flood of
        requests must not become O(rooms) work each on the event loop (a few rooms are
        always counted afresh)."""
        now = asyncio.get_running_loop().time()
        cached = self._stats.get(window)
        busy = len(self.rooms) > STATS_CACHED_FROM
        if busy and cached is not None and now - cached[0] < STATS_MAX_AGE:
            return cached[1]
        members = [c for live in self.rooms.values() for c in live.members.values()]
        stats = {
            "rooms": len(self.rooms),
            "rolling": sum(live.room.shot is not None for live in self.rooms.values()),
            "connections": len(members),
            "queued": sum(c.pending for c in members),
            "stream": self.metrics.summary(now, window),
        }
        if len(self._stats) > 16:
            self._stats.clear()
        self._stats[window] = (now, stats)
        return stats

    async def run_watchdog(self) -> None:
        """A few checks a second for all connections: cheaper than a timer per send."""
        loop = asyncio.get_running_loop()
        interval = min(1.0, self.settings.send_timeout / 4)
        while True:
            await asyncio.sleep(interval)
            self.check_senders(loop.time())

    def close_all(self, code: int, reason: str) -> None:
        for live in self.rooms.values():
            live.close(code, reason)
