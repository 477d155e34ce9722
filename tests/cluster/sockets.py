"""Room sockets on real servers by their `ws_url` (the readers are `tests.support.live`'s;
a shot's binary motion arrives decoded, which the cluster tests do not look at)."""

from __future__ import annotations

from typing import Any

import websockets

from tests.support.live import greet, place_cue, recv, send, until

__all__ = ["connect", "place_cue", "recv", "send", "until"]


async def connect(url: str, token: str | None, origin: str | None = None) -> tuple[Any, dict, dict]:
    """Open the room socket at `url` (a `ws_url`) with `token` (as a page of `origin`
    would); the `welcome` and `state` (and the own `presence` after them, read too)."""
    ws = await websockets.connect(
        url + (f"?token={token}" if token else ""),
        origin=origin,  # type: ignore[arg-type]
    )
    welcome, state = await greet(ws)
    return ws, welcome, state
