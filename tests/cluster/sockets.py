"""Room sockets on real servers, read without caring how a shot's motion is encoded: JSON
text messages as dicts, a binary message as `{"type": "binary"}` (the cluster tests check
seats, turns, results and history, not the motion format)."""

from __future__ import annotations

import asyncio
import json
from typing import Any

import websockets


async def recv(ws: Any, timeout: float = 30) -> dict:
    data = await asyncio.wait_for(ws.recv(), timeout)
    return {"type": "binary"} if isinstance(data, bytes) else json.loads(data)


async def until(ws: Any, kind: str, timeout: float = 30) -> list[dict]:
    """Messages up to and including the first of type `kind`."""
    out = []
    while True:
        out.append(await recv(ws, timeout))
        if out[-1]["type"] == kind:
            return out


async def send(ws: Any, message: dict) -> None:
    await ws.send(json.dumps(message))


async def connect(url: str, token: str | None, origin: str | None = None) -> tuple[Any, dict, dict]:
    """Open the room socket at `url` (a `ws_url`) with `token` (as a page of `origin`
    would); the `welcome` and `state` (and the own `presence` after them, read too)."""
    ws = await websockets.connect(
        url + (f"?token={token}" if token else ""),
        origin=origin,  # type: ignore[arg-type]
    )
    welcome, state, presence = await recv(ws), await recv(ws), await recv(ws)
    assert (welcome["type"], state["type"], presence["type"]) == ("welcome", "state", "presence")
    return ws, welcome, state


async def place_cue(shooter: Any, x: float, y: float) -> dict:
    """Ball in hand: put the cue ball at (x, y); returns the `state` the shooter gets."""
    await send(shooter, {"type": "place_cue", "x": x, "y": y})
    while (reply := await recv(shooter))["type"] not in ("state", "error"):
        pass
    assert reply["type"] == "state", reply
    return reply
