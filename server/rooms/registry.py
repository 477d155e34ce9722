"""All live rooms of this process, the sweeper that expires idle ones, and the watchdog
that drops members who stopped reading."""

from __future__ import annotations

import asyncio
import logging

from server.config import Settings
from server.store import RoomSnapshot

from .clock import SYSTEM_CLOCK, Clock, SeedSource
from .errors import ActionError
from .live import LiveRoom
from .metrics import StreamMetrics
from .observer import RoomObserver
from .room import Room
from .shot_runner import ShotRunner
from .snapshot import room_from_snapshot
from .tokens import new_room_id

log = logging.getLogger(__name__)
CLOSE_EXPIRED = 1001


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
        self.metrics = StreamMetrics()
        self.runner = ShotRunner(
            settings.shot_workers, settings.frame_every, settings.frames_per_message
        )

    def create(self, game: str, race_to: int = 1, shot_clock: float | None = None) -> LiveRoom:
        if len(self.rooms) >= self.settings.max_rooms:
            raise ActionError("too_many_rooms", "The server is full; try again later.")
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
        )
        live = LiveRoom(room, self.settings, self.observer, self.clock)
        self._share(live)
        self.rooms[room_id] = live
        if self.observer is not None:
            self.observer.room_changed(room)
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
            live = LiveRoom(saved.room, self.settings, self.observer, self.clock)
            if self.observer is not None:
                self.observer.room_restored(saved.room, saved.match_id)
            self._share(live)
            self.rooms[saved.room.room_id] = live
            live.resume(saved.pending)
            restored.append(live)
        if restored:
            log.info("restored %d rooms", len(restored))
        return restored

    def _share(self, live: LiveRoom) -> None:
        live.metrics = self.metrics
        live.runner = self.runner

    def get(self, room_id: str) -> LiveRoom | None:
        return self.rooms.get(room_id)

    def listing(self) -> list[LiveRoom]:
        return sorted(self.rooms.values(), key=lambda r: r.room.created_at, reverse=True)

    def sweep(self, now: float | None = None) -> list[str]:
        """Close and forget rooms nobody has used for their time to live."""
        now = self.clock.monotonic() if now is None else now
        gone = [rid for rid, live in self.rooms.items() if live.is_idle(now)]
        for rid in gone:
            self.rooms.pop(rid).close(CLOSE_EXPIRED, "expired")
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

    def stats(self, window: float) -> dict:
        """Rooms, members and the frame send lateness of the last `window` seconds."""
        now = asyncio.get_running_loop().time()
        members = [c for live in self.rooms.values() for c in live.members.values()]
        return {
            "rooms": len(self.rooms),
            "rolling": sum(live.room.shot is not None for live in self.rooms.values()),
            "connections": len(members),
            "queued": sum(c.pending for c in members),
            "stream": self.metrics.summary(now, window),
        }

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
