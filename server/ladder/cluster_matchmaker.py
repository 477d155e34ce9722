"""Play now across processes (cluster mode, `POOL_REDIS_URL`): the queue is a Redis hash
any process adds to and removes from, and one process at a time (the holder of a short
Redis lock) drains it: it reads every entry, pairs them with the same `MatchPool` as one
process, takes each pair out of the hash atomically (a Lua script: both still there, or
nothing), opens the room here (the cluster registers every new room) and leaves each
player's seat in Redis, where the process holding their long-poll reads it.

Times are wall clock seconds (`since` is compared across processes).
"""

from __future__ import annotations

import asyncio
import json
import logging
from dataclasses import asdict
from typing import Any

from redis.asyncio import Redis

from server.cluster import Cluster
from server.players import MatchPool, Pairing, Waiting, Window, nearest_level
from server.rooms import ActionError, LiveRoom, RoomRegistry

from .matchmaker import Matchmaker
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
PREFIX = "pool:playnow:"
ENTRIES = PREFIX + "entries"  # hash: player id -> JSON `Waiting`
PAIRING = PREFIX + "pairing"  # hash: the same, for players whose room is being opened
LOCK = PREFIX + "drain"  # the process pairing now: "<node>", expiring
LOCK_MS = 5000
WAVE_EVERY = 1.0  # s between two attempts to drain
POLL_EVERY = 0.2  # s between two reads of a waiting player's state, while long-polling

# KEYS: entries, pairing. ARGV: two player ids. Both moved out of the queue into
# "pairing" (still waiting, as far as they can tell), or neither (one of them left).
TAKE_PAIR = """
local a = redis.call('HGET', KEYS[1], ARGV[1])
local b = redis.call('HGET', KEYS[1], ARGV[2])
if a and b then
  redis.call('HDEL', KEYS[1], ARGV[1], ARGV[2])
  redis.call('HSET', KEYS[2], ARGV[1], a, ARGV[2], b)
  return 1
end
return 0
"""
# KEYS: lock. ARGV: node. Let go of the lock if still ours.
RELEASE = """
if redis.call('GET', KEYS[1]) == ARGV[1] then return redis.call('DEL', KEYS[1]) end
return 0
"""


def assignment_key(player_id: str) -> str:
    return f"{PREFIX}seat:{player_id}"


class ClusterMatchmaker(PlayNow):
    """`PlayNow` over Redis: every process queues and reads here, one drains."""

    def __init__(
        self, registry: RoomRegistry, results: RankedResults, window: Window, cluster: Cluster
    ) -> None:
        self.registry = registry
        self.results = results
        self.data = results.data
        self.window = window
        self.cluster = cluster
        self.redis: Redis = cluster.redis
        self.node = cluster.node
        # Opens and watches the rooms of the pairs drained here (its own pool stays empty).
        self.local = Matchmaker(registry, results, window)
        self._seen: set[str] = set()  # rooms of this process checked for being ranked
        self._take_pair = self.redis.register_script(TAKE_PAIR)
        self._release = self.redis.register_script(RELEASE)

    def now(self) -> float:
        return self.registry.clock.wall()

    async def _entry(self, player_id: str, pairing: bool = False) -> Waiting | None:
        raw = await self.redis.hget(ENTRIES, player_id)
        if raw is None and pairing:
            raw = await self.redis.hget(PAIRING, player_id)
        return None if raw is None else Waiting(**json.loads(raw))

    async def enqueue(self, entry: Waiting) -> None:
        """One entry a player: the same game keeps the place, another replaces it."""
        held = await self._entry(entry.player_id)
        if held is None or held.kind != entry.kind:
            await self.redis.delete(assignment_key(entry.player_id))
            await self.redis.hset(ENTRIES, entry.player_id, json.dumps(asdict(entry)))
        await self.wave()

    async def dequeue(self, player_id: str) -> None:
        await self.redis.hdel(ENTRIES, player_id)

    async def status(self, player_id: str) -> dict[str, Any]:
        raw = await self.redis.get(assignment_key(player_id))
        if raw is not None:
            assignment = Assignment(**json.loads(raw))
            if not match_over(self.registry, assignment, gone_is_over=False):
                return matched(assignment)
            await self.redis.delete(assignment_key(player_id))
        entry = await self._entry(player_id, pairing=True)
        if entry is None:
            return {"status": "idle"}
        return waiting(entry, self.now(), self.window, self._offer(entry))

    def _offer(self, entry: Waiting) -> str | None:
        if self.now() - entry.since < self.window.computer_after:
            return None
        return nearest_level(entry.rating)

    async def wait(self, player_id: str, timeout: float) -> None:
        """Until the player's state changes (read from Redis every `POLL_EVERY` s)."""
        first = await self.status(player_id)
        if first["status"] != "waiting":
            return
        loop = asyncio.get_running_loop()
        deadline = loop.time() + timeout
        while loop.time() < deadline:
            await asyncio.sleep(min(POLL_EVERY, max(0.0, deadline - loop.time())))
            now = await self.status(player_id)
            if now["status"] != "waiting" or (now["computer"] and not first["computer"]):
                return

    async def take_computer(self, player_id: str, key: str) -> tuple[Assignment, str]:
        entry = await self._entry(player_id)
        level = None if entry is None else self._offer(entry)
        if entry is None or level is None:
            raise ActionError("not_offered", "The computer is offered after a while alone.")
        if not await self.redis.hdel(ENTRIES, player_id):
            raise ActionError("not_offered", "You are no longer waiting.")
        live = self.registry.create(
            entry.kind, self.registry.settings.playnow_race_to, listed=False, opponent=level
        )
        assignment = seat_alone(live, player_id, entry.name, key, self.data, self.now())
        await self._registered(live)
        await self._assign(player_id, assignment)
        return assignment, level

    async def _registered(self, live: LiveRoom) -> None:
        """Wait until the cluster knows the room (any process can then find it), so a
        player sent there never finds it missing; if Redis or the store cannot be reached
        the cluster tries again at its heartbeat, and the players are sent anyway."""
        if self.cluster.epoch_of(live.room.room_id) is not None:
            return  # registered already
        try:
            # The registry started this when it created the room (the same task, still
            # running: nothing was awaited since).
            await asyncio.shield(self.cluster.own_new(live))
        except Exception:
            log.exception("play now: room %s not registered yet", live.room.room_id)

    async def _assign(self, player_id: str, assignment: Assignment) -> None:
        text = json.dumps(asdict(assignment))
        await self.redis.set(assignment_key(player_id), text, ex=int(ASSIGNMENT_KEPT))

    async def wave(self) -> int:
        """Drain the queue if no other process is: pair, take each pair out atomically,
        open its room here. Returns the rooms opened."""
        if not await self.redis.set(LOCK, self.node, nx=True, px=LOCK_MS):
            return 0
        try:
            # A drainer that died between taking a pair and seating it left it here (a
            # wave takes milliseconds; the lock lasts seconds): back into the queue.
            for player_id, text in (await self.redis.hgetall(PAIRING)).items():
                await self.redis.hsetnx(ENTRIES, player_id, text)
            await self.redis.delete(PAIRING)
            raw = await self.redis.hgetall(ENTRIES)
            pool = MatchPool(self.window)
            entries = sorted((Waiting(**json.loads(v)) for v in raw.values()), key=_since)
            for entry in entries:
                pool.put_back(entry)
            opened = 0
            for pairing in pool.pair(self.now()):
                if await self._open(pairing):
                    opened += 1
            return opened
        finally:
            await self._release(keys=[LOCK], args=[self.node])

    async def _open(self, pairing: Pairing) -> bool:
        first, second = pairing.first.player_id, pairing.second.player_id
        if not await self._take_pair(keys=[ENTRIES, PAIRING], args=[first, second]):
            return False  # one of them left meanwhile
        try:
            self.local.open_room(pairing)
        except ActionError as exc:
            log.warning("play now: no room for a pair (%s); both wait on", exc.code)
            for entry in (pairing.first, pairing.second):
                await self.redis.hset(ENTRIES, entry.player_id, json.dumps(asdict(entry)))
            await self.redis.hdel(PAIRING, first, second)
            return False
        assignments = [self.local.assignments.pop(p) for p in (first, second)]
        live = self.registry.get(assignments[0].room_id)
        if live is not None:
            await self._registered(live)
        for player_id, assignment in zip((first, second), assignments, strict=True):
            await self._assign(player_id, assignment)
        await self.redis.hdel(PAIRING, first, second)
        return True

    async def queued(self) -> set[str]:
        waiting = await self.redis.hkeys(ENTRIES)
        pairing = await self.redis.hkeys(PAIRING)
        keys = {k if isinstance(k, str) else k.decode() for k in (*waiting, *pairing)}
        return keys | await self.local.queued()

    async def resume(self) -> int:
        return await self.watch_new_rooms()

    async def watch_new_rooms(self) -> int:
        """Rooms this process took over from another (a failover, a deploy) may be ranked:
        watch those so their result is rated here."""
        new = [room_id for room_id in self.registry.rooms if room_id not in self._seen]
        if not new:
            return 0
        self._seen.update(new)
        self._seen.intersection_update(self.registry.rooms)
        return self.results.restore(await self.data.open_ranked(new))

    async def run(self) -> None:
        while True:
            await asyncio.sleep(WAVE_EVERY)
            try:
                await self.wave()
                await self.watch_new_rooms()
            except Exception:  # Redis or the store out of reach: the next wave tries again
                log.exception("play now: a wave failed")


def _since(entry: Waiting) -> float:
    return entry.since
