"""Guest pruning: a profile is made by a first visit, so anyone can make thousands (120 in
0.7 s from six addresses); those that never played are deleted `POOL_GUEST_TTL` after they
were made, checked every `POOL_GUEST_PRUNE_EVERY` s by each process (a delete of the same
rows twice deletes nothing more). A pruned guest's browser simply gets a new profile on its
next visit: it had nothing to lose.
"""

from __future__ import annotations

import asyncio
import logging
from dataclasses import dataclass

from server.rooms import Clock

from .player_data import PlayerData
from .playnow import PlayNow

log = logging.getLogger(__name__)
BATCH = 1000  # guests deleted per statement: each write stays short


@dataclass
class GuestPruning:
    data: PlayerData
    playnow: PlayNow
    clock: Clock
    ttl: float  # s after its creation a guest that never played is deleted
    every: float  # s between two prunings

    async def prune(self) -> int:
        """Delete the guests made more than `ttl` ago that never played (none waiting for
        Play now); how many were."""
        created_before = self.clock.wall() - self.ttl
        keep = await self.playnow.queued()
        pruned = 0
        while True:
            deleted = await self.data.prune_guests(created_before, keep, BATCH)
            pruned += deleted
            if deleted < BATCH:
                return pruned

    async def run(self) -> None:
        """Prune now and every `every` s, for ever (the lifespan's background task)."""
        while True:
            try:
                pruned = await self.prune()
            except Exception:  # the store or Redis out of reach: the next round tries again
                log.exception("guest pruning failed")
            else:
                if pruned:
                    log.info("pruned %d guests that never played", pruned)
            await asyncio.sleep(self.every)
