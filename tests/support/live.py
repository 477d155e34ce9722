"""A real uvicorn in a thread on a real port, and the asyncio `websockets` readers for it."""

from __future__ import annotations

import asyncio
import json
from contextlib import AbstractContextManager
from typing import Any

import httpx

from server.config import Settings
from tests.support.embedded import bound_socket, serving

from .games import EIGHT_BALL
from .messages import decoded
from .rooms import app_with


def live_server(
    settings: Settings, seed: int = EIGHT_BALL, port: int = 0
) -> AbstractContextManager[str]:
    """`app_with(settings, seed)` served on 127.0.0.1:`port` (0: a free one) over the
    database at `settings.db_path`; yields "host:port"."""
    return serving(app_with(settings, seed), settings, bound_socket(port))


def http(address: str) -> httpx.Client:
    """An HTTP client of the server at `address` (for `rooms.seated_room` and friends)."""
    return httpx.Client(base_url=f"http://{address}", timeout=20)


def ws_url(address: str, room_id: str, token: str | None = None) -> str:
    return f"ws://{address}/ws/rooms/{room_id}" + (f"?token={token}" if token else "")


async def recv(ws: Any, timeout: float = 30) -> dict:
    """The next message; the binary `motion` message decoded (`messages.decoded`)."""
    return decoded(await asyncio.wait_for(ws.recv(), timeout))


async def until(ws: Any, kind: str, timeout: float = 30) -> list[dict]:
    """Messages up to and including the first of type `kind`."""
    out = []
    while True:
        out.append(await recv(ws, timeout))
        if out[-1]["type"] == kind:
            return out


async def greet(ws: Any) -> tuple[dict, dict]:
    """The `welcome`, `state` and own `presence` a new connection gets first."""
    welcome, state, presence = await recv(ws), await recv(ws), await recv(ws)
    assert (welcome["type"], state["type"], presence["type"]) == ("welcome", "state", "presence")
    return welcome, state


async def send(ws: Any, message: dict) -> None:
    await ws.send(json.dumps(message))


async def place_cue(shooter: Any, x: float, y: float) -> dict:
    """Ball in hand: put the cue ball at (x, y); returns the `state` the shooter gets."""
    await send(shooter, {"type": "place_cue", "x": x, "y": y})
    while (reply := await recv(shooter))["type"] not in ("state", "error"):
        pass
    assert reply["type"] == "state", reply
    return reply
