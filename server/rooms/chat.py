"""A room's chat: each line within its sender's credits and, for spectators, within the
credits of all spectators together, so no crowd can drown the players."""

from __future__ import annotations

from server.config import Settings

from .clock import Clock
from .connection import Connection
from .errors import ActionError
from .ratelimit import TokenBucket
from .room import Room
from .stream import RoomStream


class RoomChat:
    def __init__(self, room: Room, stream: RoomStream, settings: Settings, clock: Clock) -> None:
        self.room = room
        self.stream = stream
        self.clock = clock
        # All spectators together: however many there are, the players get at most this.
        self._crowd = TokenBucket(
            settings.crowd_chat_burst, settings.crowd_chat_per_second, clock.monotonic
        )

    def say(self, conn: Connection, text: str) -> None:
        """A chat line to everyone; a refusal is told once per streak (`ActionError`), then
        dropped without a reply."""
        refusal = self._refusal(conn)
        if refusal is not None:
            if conn.first_refusal():
                raise refusal
            return
        line = "".join(ch if ch.isprintable() else " " for ch in text).strip()
        if not line:
            raise ActionError("bad_message", "text: the message is empty")
        conn.accepted()
        self.stream.broadcast(self.room.say(conn.seat, line, self.clock.wall()), social=True)

    def _refusal(self, conn: Connection) -> ActionError | None:
        if not conn.chat_allowed():
            return ActionError("chat_rate_limited", "Too many chat messages; wait a moment.")
        if conn.seat is None and not self._crowd.take():
            return ActionError("chat_busy", "The spectators' chat is full; wait a moment.")
        return None
