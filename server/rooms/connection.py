"""One client's outbox: a bounded queue drained by its own sender task.

The room never awaits a client. `push` only appends; when the queue is full the oldest
droppable message (a stale frame or aim relay) goes first, and a client that is still
too far behind is closed with 1013 so it reconnects and gets a fresh `state`. Social
messages (chat, presence) hold at most a quarter of the queue and are the first to go: a
crowd of chatting spectators can cost a player some chat lines, never the game's messages
or the connection. Sending what
is queued has a deadline (watched by the registry), so a peer that stops reading is dropped
instead of holding anything up.
"""

from __future__ import annotations

import asyncio
import contextlib
import itertools
from collections import deque
from collections.abc import Awaitable, Callable
from dataclasses import dataclass, field
from typing import Any

from .ratelimit import TokenBucket

CLOSE_TOO_SLOW = 1013
GAME, DROPPABLE, SOCIAL = 0, 1, 2  # message priorities, most needed first
CLOSE_REPLACED = 4000

_ids = itertools.count(1)


@dataclass
class Connection:
    """A room member. `seat` is None for a spectator."""

    send_text: Callable[[str], Awaitable[None]]
    seat: int | None
    name: str | None
    limit: int = 64
    send_timeout: float = 5.0
    id: int = field(default_factory=lambda: next(_ids))
    dropped: int = 0  # messages skipped because the client was behind
    on_drop: Callable[[], None] | None = None  # told of each (the server's count of them)
    close_code: int | None = None  # set when the room wants this connection gone
    close_reason: str = ""
    flushing: bool = False  # closing, but sending what is queued first
    _queue: deque[tuple[str | bytes, int]] = field(default_factory=deque)  # (message, priority)
    _social: int = 0  # social messages in the queue
    chat_credit: TokenBucket | None = None  # None: chat is not limited
    _wake: asyncio.Event = field(default_factory=asyncio.Event)
    _refusing: bool = False  # chat refused since the last accepted line (told once)
    _sending_since: float | None = None  # loop time the batch being sent started
    _sender: asyncio.Task[None] | None = None
    # Binary messages (a shot's `motion`); without it they are not sent (test doubles).
    send_bytes: Callable[[bytes], Awaitable[None]] | None = None

    def push(self, text: str | bytes, droppable: bool = False, social: bool = False) -> None:
        """Queue a message without waiting; never blocks the caller. `droppable`: a newer
        one supersedes it (frames, aim); `social`: chat and presence, kept only while
        there is room."""
        if self.close_code is not None:
            return
        priority = SOCIAL if social else DROPPABLE if droppable else GAME
        if priority == SOCIAL and self._social >= max(1, self.limit // 4):
            self._drop_oldest(SOCIAL)
        if len(self._queue) >= self.limit and not (
            self._drop_oldest(DROPPABLE) or self._drop_oldest(SOCIAL)
        ):
            if priority != GAME:
                self._count_drop()
                return
            self.close(CLOSE_TOO_SLOW, "too_slow")
            return
        self._queue.append((text, priority))
        self._social += priority == SOCIAL
        self._wake.set()

    def _drop_oldest(self, priority: int) -> bool:
        for i, (_, kind) in enumerate(self._queue):
            if kind == priority:
                del self._queue[i]
                self._count_drop()
                self._social -= priority == SOCIAL
                return True
        return False

    def _count_drop(self) -> None:
        self.dropped += 1
        if self.on_drop is not None:
            self.on_drop()

    def chat_allowed(self) -> bool:
        """Spend a chat credit (a bucket per sender, as lichess does)."""
        return self.chat_credit is None or self.chat_credit.take()

    def first_refusal(self) -> bool:
        """True for the first refused chat since the last accepted one: the sender is told
        once, the rest of the streak is dropped without a reply (a flood of refusals would
        cost the server a message out for every message in)."""
        first = not self._refusing
        self._refusing = True
        return first

    def accepted(self) -> None:
        self._refusing = False

    def close(self, code: int, reason: str, flush: bool = False) -> None:
        """Ask the sender to stop; the transport closes the socket with `code`. `flush`:
        what is queued still goes out first (the replies a client is owed before a policy
        close), under the usual send deadline."""
        if self.close_code is None:
            self.close_code = code
            self.close_reason = reason
            self.flushing = flush
            if not flush:
                self._queue.clear()
                self._social = 0
        self._wake.set()

    @property
    def pending(self) -> int:
        return len(self._queue)

    async def run_sender(self) -> None:
        """Send queued messages in order until closed; returns when the room closed us.

        What is queued when a batch starts goes out under one deadline, checked by the
        registry's watchdog (`check_deadline`) rather than a timer per message: a peer that
        cannot take its backlog in `send_timeout` is dropped."""
        self._sender = asyncio.current_task()
        loop = asyncio.get_running_loop()
        while True:
            while not self._queue and self.close_code is None:
                self._wake.clear()
                await self._wake.wait()
            if self.close_code is not None and not (self.flushing and self._queue):
                return
            self._sending_since = loop.time()
            try:
                for _ in range(len(self._queue)):
                    if not self._queue or (self.close_code is not None and not self.flushing):
                        break
                    text, priority = self._queue.popleft()
                    self._social -= priority == SOCIAL
                    if isinstance(text, str):
                        await self.send_text(text)
                    elif self.send_bytes is not None:
                        await self.send_bytes(text)
            finally:
                self._sending_since = None

    def check_deadline(self, now: float) -> bool:
        """Drop the client (1013) if its current batch has been sending for longer than
        `send_timeout` (loop time `now`); True if it was dropped."""
        since = self._sending_since
        if since is None or now - since <= self.send_timeout or self.close_code is not None:
            return False
        self.close(CLOSE_TOO_SLOW, "too_slow")
        if self._sender is not None:
            self._sender.cancel()
        return True


async def cancel_quietly(task: asyncio.Task[Any]) -> None:
    task.cancel()
    with contextlib.suppress(asyncio.CancelledError, Exception):
        await task
