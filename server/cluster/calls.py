"""Calls between processes over Redis pub/sub: each process listens on its own inbox
channel; a call is a message there and its answer a message on the caller's inbox. Used to
run a request where its room is played, and to hand rooms over (`adopt`)."""

from __future__ import annotations

import asyncio
import contextlib
import json
import logging
import secrets
from collections.abc import Awaitable, Callable
from dataclasses import dataclass
from typing import Any

from redis.asyncio import Redis
from redis.exceptions import RedisError

from . import keys
from .background import Background

log = logging.getLogger(__name__)
Handler = Callable[[dict[str, Any]], Awaitable[tuple[int, dict[str, Any]]]]
Adopt = Callable[[list[str], str], Awaitable[object]]


class Unreachable(Exception):
    """Another process (or Redis itself) did not answer in time."""


@dataclass(frozen=True)
class Forwarded:
    """What another process answered to a call: an HTTP status and its JSON body."""

    status: int
    body: dict[str, Any]


class Inbox:
    def __init__(self, redis: Redis, node: str, timeout: float) -> None:
        self.redis = redis
        self.node = node
        self.timeout = timeout
        self.handlers: dict[str, Handler] = {}  # calls other processes may make here
        self.on_adopt: Adopt | None = None  # rooms handed over to this process
        self._calls: dict[str, asyncio.Future[Forwarded]] = {}
        self._pubsub = redis.pubsub(ignore_subscribe_messages=True)
        self.background = Background()  # calls being answered, rooms being adopted

    async def start(self) -> None:
        await self._pubsub.subscribe(keys.inbox(self.node))

    async def close(self) -> None:
        with contextlib.suppress(Exception):
            await self._pubsub.aclose()

    async def call(
        self, node: str, op: str, args: dict[str, Any], timeout: float | None = None
    ) -> Forwarded:
        """Run handler `op` on process `node` (here when it is this one); raises
        `Unreachable` when no answer comes within `timeout` (else the inbox's)."""
        if node == self.node:
            status, body = await self.handlers[op](args)
            return Forwarded(status, body)
        call_id = secrets.token_hex(8)
        future: asyncio.Future[Forwarded] = asyncio.get_running_loop().create_future()
        self._calls[call_id] = future
        try:
            message = {"kind": "call", "id": call_id, "from": self.node, "op": op, "args": args}
            if not await self.send(node, message):
                raise Unreachable(node)
            return await asyncio.wait_for(future, timeout or self.timeout)
        except (TimeoutError, RedisError, OSError):
            raise Unreachable(node) from None
        finally:
            self._calls.pop(call_id, None)

    async def send(self, node: str, message: dict[str, Any]) -> bool:
        """Publish to `node`'s inbox; False when nobody listens there."""
        return bool(await self.redis.publish(keys.inbox(node), json.dumps(message)))

    async def run(self) -> None:
        """Read the inbox for ever (again after Redis comes back)."""
        while True:
            try:
                async for message in self._pubsub.listen():
                    if message.get("type") == "message":
                        self._received(json.loads(message["data"]))
            except (RedisError, OSError) as exc:
                log.warning("cluster: inbox: %s; listening again in 1 s", exc)
                await asyncio.sleep(1.0)
                with contextlib.suppress(RedisError, OSError):
                    await self._pubsub.subscribe(keys.inbox(self.node))

    def _received(self, data: dict[str, Any]) -> None:
        kind = data.get("kind")
        if kind == "reply":
            future = self._calls.get(data["id"])
            if future is not None and not future.done():
                future.set_result(Forwarded(int(data["status"]), data["body"]))
        elif kind == "call":
            self.background.start(self._answer(data))
        elif kind == "adopt" and self.on_adopt is not None:
            self.background.start(self._adopt(self.on_adopt, data["rooms"], data["from"]))

    async def _answer(self, data: dict[str, Any]) -> None:
        handler = self.handlers.get(data["op"])
        if handler is None:
            status, body = 404, {"code": "unknown_call", "message": data["op"]}
        else:
            try:
                status, body = await handler(data["args"])
            except Exception:
                log.exception("cluster: call %s failed", data["op"])
                status, body = 500, {"code": "internal", "message": "The call failed."}
        reply = {"kind": "reply", "id": data["id"], "status": status, "body": body}
        with contextlib.suppress(RedisError, OSError):
            await self.send(data["from"], reply)

    @staticmethod
    async def _adopt(adopt: Adopt, rooms: list[str], source: str) -> None:
        try:
            await adopt(rooms, source)
        except Exception:
            log.exception("cluster: adopting rooms from %s failed", source)
