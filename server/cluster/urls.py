"""Where a client connects for a room."""

from __future__ import annotations

from urllib.parse import quote


def ws_url(base_url: str, room_id: str) -> str:
    """The absolute WebSocket URL of `room_id` on the server at `base_url` (http(s)://...)."""
    base = base_url.rstrip("/")
    if base.startswith("https://"):
        base = "wss://" + base[len("https://") :]
    elif base.startswith("http://"):
        base = "ws://" + base[len("http://") :]
    return f"{base}/ws/rooms/{quote(room_id, safe='')}"
