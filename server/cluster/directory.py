"""The shared room list: each owner publishes its rooms' lobby summaries (those that
changed since it last did), any process reads a page of all of them, newest first."""

from __future__ import annotations

import contextlib
import json
from collections.abc import Iterable
from typing import Any

from redis.asyncio import Redis
from redis.exceptions import RedisError

from server.rooms import LiveRoom

from . import keys
from .calls import Unreachable


class Directory:
    def __init__(self, redis: Redis, node: str) -> None:
        self.redis = redis
        self.node = node
        self._published: dict[str, str] = {}  # room id -> the entry last published

    async def publish(self, lives: Iterable[LiveRoom], force: bool = False) -> int:
        """Write the summaries that changed since last time (all with `force`); returns
        how many."""
        changed = []
        for live in lives:
            room = live.room
            entry = json.dumps({"node": self.node, "listed": room.listed, **room.summary()})
            if force or self._published.get(room.room_id) != entry:
                changed.append((room, entry))
        if not changed:
            return 0
        async with self.redis.pipeline(transaction=False) as pipe:
            for room, entry in changed:
                pipe.set(keys.room(room.room_id), entry)
                if room.listed:
                    pipe.zadd(keys.LISTED, {room.room_id: room.created_at})
            await pipe.execute()
        for room, entry in changed:
            self._published[room.room_id] = entry
        return len(changed)

    def forget(self, room_id: str) -> None:
        """No longer published from here (closed, or played elsewhere now)."""
        self._published.pop(room_id, None)

    async def listing(self, offset: int, limit: int) -> tuple[list[dict[str, Any]], int]:
        """A page of the listed rooms of every process, newest first, and how many there
        are; `Unreachable` without Redis."""
        try:
            async with self.redis.pipeline(transaction=False) as pipe:
                pipe.zcard(keys.LISTED)
                pipe.zrevrange(keys.LISTED, offset, offset + limit - 1)
                total, ids = await pipe.execute()
            if not ids:
                return [], int(total)
            entries = await self.redis.mget([keys.room(r) for r in ids])
        except (RedisError, OSError) as exc:
            raise Unreachable("redis") from exc
        rooms, missing = [], []
        for room_id, entry in zip(ids, entries, strict=True):
            if entry is None:  # closed meanwhile
                missing.append(room_id)
                continue
            data = json.loads(entry)
            data.pop("node", None)
            data.pop("listed", None)
            rooms.append(data)
        if missing:
            with contextlib.suppress(RedisError, OSError):
                await self.redis.zrem(keys.LISTED, *missing)
        return rooms, int(total) - len(missing)

    async def known(self, room_id: str) -> bool:
        """Whether any process has published the room (it exists, wherever it is)."""
        try:
            return bool(await self.redis.exists(keys.room(room_id)))
        except (RedisError, OSError) as exc:
            raise Unreachable("redis") from exc
