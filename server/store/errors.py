"""What the store raises for a caller to act on."""

from __future__ import annotations


class StaleOwner(Exception):
    """A write (or claim) for a room carried an ownership epoch lower than the one stored:
    another process has taken the room over since. Nothing was written; the caller has lost
    the room and must stop playing it."""

    def __init__(self, room_id: str, epoch: int, stored: int) -> None:
        super().__init__(f"room {room_id}: epoch {epoch} is stale, {stored} owns it")
        self.room_id = room_id
        self.epoch = epoch
        self.stored = stored


class StoreUnavailable(Exception):
    """A read (or a call that waits for its answer) got none within its deadline: the
    database is out of reach or busy retrying the writes queued before it. Nothing is
    known about the answer; the caller says "try again soon" (HTTP 503 `unavailable`)."""
