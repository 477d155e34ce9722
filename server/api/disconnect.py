"""Work for a request that stops when its client leaves.

uvicorn does not cancel an HTTP handler whose client disconnected: a hint asked and given
up on (a closed tab, a client's timeout) was still planned, in a queue of such hints that
kept the computer's turns waiting for minutes. `unless_gone` runs the work beside a watch on
the request's `http.disconnect` and cancels it when that comes first.
"""

from __future__ import annotations

import asyncio
from collections.abc import Coroutine
from typing import Any, TypeVar

from fastapi import HTTPException, Request

T = TypeVar("T")
CLIENT_GONE = 499  # nginx's "client closed request": nobody reads it, the log shows it


async def _gone(request: Request) -> None:
    """Return once the client has disconnected (the body is read: nothing else comes)."""
    while (await request.receive())["type"] != "http.disconnect":
        pass


async def unless_gone(request: Request, work: Coroutine[Any, Any, T]) -> T:
    """`work`'s result, or its cancellation and `499 client_gone` when the client leaves
    before it is done."""
    task = asyncio.ensure_future(work)
    watch = asyncio.ensure_future(_gone(request))
    try:
        done, _ = await asyncio.wait({task, watch}, return_when=asyncio.FIRST_COMPLETED)
    except BaseException:  # the handler itself is cancelled (the server stops)
        task.cancel()
        raise
    finally:
        watch.cancel()
    if task in done:
        return task.result()
    task.cancel()
    await asyncio.gather(task, return_exceptions=True)  # until it has let go of its work
    raise HTTPException(
        CLIENT_GONE, {"code": "client_gone", "message": "The client left before the answer."}
    )
