"""`FanOut`: a room's messages to its members, the players' at once, the spectators' a few
per turn of the event loop.

Sending one message costs the loop tens of microseconds per socket. A room with 150
spectators spent ~10 ms of one loop turn sending a shot's `motion` or `state` to all of
them, and a player's `shoot` that arrived meanwhile waited for the whole turn. Handing the
spectators' copies out `PER_TURN` at a time lets the loop read its sockets (the players')
between batches; a spectator's messages keep their order (one queue for all of them, and a
reply to a spectator joins it while it is not empty).

While the room simulates a shot, the spectators' copies wait (`hold`): the shot's thread
needs the GIL to start and to hand its result back, and a loop busy sending a crowd's
copies of the last `state` made it wait a millisecond (the switch interval) at each step,
several times a shot.
"""

from __future__ import annotations

import asyncio
from collections import deque
from collections.abc import Iterable

from .connection import Connection

PER_TURN = 16  # spectators' copies handed out per turn of the loop


class FanOut:
    def __init__(self) -> None:
        self._queue: deque[tuple[Connection, str | bytes, bool, bool]] = deque()
        self._draining = False
        self._held = False

    def send(
        self,
        members: Iterable[Connection],
        message: str | bytes,
        droppable: bool = False,
        social: bool = False,
        exclude: Connection | None = None,
    ) -> None:
        """`message` to every member but `exclude`: players now, spectators in turn."""
        for conn in members:
            if conn is exclude:
                continue
            if conn.seat is not None:
                conn.push(message, droppable, social)
            else:
                self._queue.append((conn, message, droppable, social))
        self._schedule()

    def send_one(self, conn: Connection, message: str | bytes) -> None:
        """A reply to one member, after anything still queued for the spectators."""
        if conn.seat is None and self._queue:
            self._queue.append((conn, message, False, False))
        else:
            conn.push(message)

    @property
    def pending(self) -> int:
        return len(self._queue)

    def hold(self) -> None:
        """Keep the spectators' copies queued (the players' still go at once)."""
        self._held = True

    def release(self) -> None:
        self._held = False
        self._schedule()

    def _schedule(self) -> None:
        if self._queue and not self._draining and not self._held:
            self._draining = True
            asyncio.get_running_loop().call_soon(self._drain)

    def _drain(self) -> None:
        self._draining = False
        if self._held:
            return
        for _ in range(min(PER_TURN, len(self._queue))):
            conn, message, droppable, social = self._queue.popleft()
            conn.push(message, droppable, social)
        self._schedule()
