"""Match ids for the processes sharing one store: blocks reserved in the store ahead of
need (`repo.reserve_match_ids`), handed out without waiting on the event loop."""

from __future__ import annotations

import asyncio
import contextlib
import logging
from collections import deque

from server.store import Database

log = logging.getLogger(__name__)
AHEAD = 32


class MatchIds:
    """An iterator of ids (what `StoreObserver` takes), refilled in the background."""

    def __init__(self, store: Database) -> None:
        self.store = store
        self.ready: deque[int] = deque()
        self.last = 0
        self._refilling: asyncio.Task[None] | None = None

    def __iter__(self) -> MatchIds:
        return self

    def __next__(self) -> int:
        if len(self.ready) < AHEAD // 2 and (self._refilling is None or self._refilling.done()):
            with contextlib.suppress(RuntimeError):  # no running loop: `refill` first
                self._refilling = asyncio.get_running_loop().create_task(self.refill())
        if self.ready:
            self.last = self.ready.popleft()
        else:  # the store out of reach for a whole block: better a record than none
            log.error("no match id reserved; using %d", self.last + 1)
            self.last += 1
        return self.last

    async def refill(self) -> None:
        try:
            ids = await self.store.call(lambda repo: repo.reserve_match_ids(AHEAD))
        except Exception as exc:
            log.warning("cluster: match ids not reserved: %s", exc)
            return
        self.ready.extend(ids)

    async def stop(self) -> None:
        if self._refilling is not None:
            self._refilling.cancel()
            with contextlib.suppress(asyncio.CancelledError, Exception):
                await self._refilling
