"""Tasks a process starts and does not await (answering another process's call, clearing
a closed room's keys) are held until done: the event loop alone keeps only a weak
reference, and an unreferenced task can be garbage-collected before it finishes."""

from __future__ import annotations

import asyncio
import gc
from typing import Any

from redis.asyncio import Redis

from server.cluster.background import Background
from server.cluster.calls import Inbox


def test_a_background_task_is_held_until_done():
    async def run() -> None:
        background = Background()
        release = asyncio.Event()
        task = background.start(release.wait())
        assert background.tasks == {task}
        release.set()
        await task
        await asyncio.sleep(0)  # the done callbacks run
        assert background.tasks == set()

    asyncio.run(run())


def test_a_call_being_answered_is_held_and_its_reply_sent():
    """The inbox answers a call in a task of its own; nothing but the inbox holds it."""

    async def run() -> None:
        redis = Redis.from_url("redis://127.0.0.1:1/0")  # never reached: `send` is replaced
        inbox = Inbox(redis, "here", timeout=1.0)
        started, release = asyncio.Event(), asyncio.Event()
        replies: list[tuple[str, dict[str, Any]]] = []

        async def slow(args: dict[str, Any]) -> tuple[int, dict[str, Any]]:
            started.set()
            await release.wait()
            return 200, {"echo": args["n"]}

        async def send(node: str, message: dict[str, Any]) -> bool:
            replies.append((node, message))
            return True

        inbox.handlers["slow"] = slow
        inbox.send = send  # type: ignore[method-assign]
        inbox._received(
            {"kind": "call", "id": "c1", "from": "there", "op": "slow", "args": {"n": 7}}
        )
        await started.wait()
        gc.collect()
        assert len(inbox.background.tasks) == 1
        release.set()
        while inbox.background.tasks:
            await asyncio.sleep(0)
        assert replies == [
            ("there", {"kind": "reply", "id": "c1", "status": 200, "body": {"echo": 7}})
        ]
        await redis.aclose()

    asyncio.run(run())
