"""All live rooms of this process, the sweeper that expires idle ones, and the watchdog
that drops members who stopped reading."""

from __future__ import annotations

import asyncio
import logging
import time

from server.config import Settings

from .errors import ActionError
from .live import LiveRoom
from .metrics import StreamMetrics
from .observer import RoomObserver
from .room import Room
from .shot_runner import ShotRunner
from .tokens import new_room_id

log = logging.getLogger(__name__)
CLOSE_EXPIRED = 1001


class RoomRegistry:
    """Creates, finds, lists and expires rooms. One process owns its rooms (one worker)."""

    def __init__(self, settings: Settings, observer: RoomObserver | None = None) -> None:
        self.settings = settings
        self.observer = observer
        self.rooms: dict[str, LiveRoom] = {}
        self.metrics = StreamMetrics()
        self.runner = ShotRunner(settings.shot_workers, settings.frame_every,
                                 settings.frames_per_message)

    def create(self, game: str, race_to: int = 1, shot_clock: float | None = None) -> LiveRoom:
        if len(self.rooms) >= self.settings.max_rooms:
            raise ActionError("too_many_rooms", "The server is full; try again later.")
        room_id = new_room_id()
        while room_id in self.rooms:
            room_id = new_room_id()
        clock = self.settings.shot_clock if shot_clock is None else shot_clock
        room = Room(room_id, game, race_to=race_to, shot_clock=clock, created_at=time.time())
        live = LiveRoom(room, self.settings, self.observer)
        self._share(live)
        self.rooms[room_id] = live
        if self.observer is not None:
            self.observer.room_changed(room)
        return live

    def add(self, live: LiveRoom) -> None:
        """Put back a restored room (storage, issue 7)."""
        self._share(live)
        self.rooms[live.room.room_id] = live

    def _share(self, live: LiveRoom) -> None:
        live.metrics = self.metrics
        live.runner = self.runner

    def get(self, room_id: str) -> LiveRoom | None:
        return self.rooms.get(room_id)

    def listing(self) -> list[LiveRoom]:
        return sorted(self.rooms.values(), key=lambda r: r.room.created_at, reverse=True)

    def sweep(self, now: float | None = None) -> list[str]:
        """Close and forget rooms nobody has used for their time to live."""
        now = time.monotonic() if now is None else now
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
        return sum(conn.check_deadline(now) for live in list(self.rooms.values())
                   for conn in list(live.members.values()))

    def stats(self, window: float) -> dict:
        """Rooms, members and the frame send lateness of the last `window` seconds."""
        now = asyncio.get_running_loop().time()
        members = [c for live in self.rooms.values() for c in live.members.values()]
        return {"rooms": len(self.rooms),
                "rolling": sum(live.room.shot is not None for live in self.rooms.values()),
                "connections": len(members),
                "queued": sum(c.pending for c in members),
                "stream": self.metrics.summary(now, window)}

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
