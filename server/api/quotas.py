"""Per-client limits on what costs the server: opening rooms, taking seats, opening
spectator sockets, making profiles, pressing Play now. A client is its address (a player
for Play now); the limits come from settings in the `limits` library's notation
("30/minute"), counted in a moving window, so one script cannot take every room or seat.
Over its limit, an HTTP request is refused with 429 `rate_limited` (`ClientQuotas.enforce`)."""

from __future__ import annotations

from fastapi import HTTPException
from limits import RateLimitItem, parse
from limits.storage import MemoryStorage
from limits.strategies import MovingWindowRateLimiter

from server.config import Settings

# What a refused request is told, per action (spectator sockets are closed instead).
REFUSALS = {
    "create": "Too many new tables; wait a minute.",
    "join": "Too many seats taken; wait a minute.",
    "player": "Too many new profiles; wait a minute.",
    "queue": "Too many Play now presses; wait a minute.",
}


class ClientQuotas:
    def __init__(self, settings: Settings) -> None:
        self._limiter = MovingWindowRateLimiter(MemoryStorage())
        self._items: dict[str, RateLimitItem] = {
            "create": parse(settings.room_create_rate),
            "join": parse(settings.join_rate),
            "watch": parse(settings.watch_rate),  # spectator sockets, per address
            "player": parse(settings.player_create_rate),  # new profiles, per address
            "queue": parse(settings.queue_rate),  # Play now joins and leaves, per player
        }

    def allow(self, action: str, client: str) -> bool:
        """Count one `action` ("create", "join", "watch", "player" or "queue") by `client` (an
        address; a player id for "queue"); False once over its limit."""
        return self._limiter.hit(self._items[action], action, client)

    def enforce(self, action: str, client: str) -> None:
        """Count one `action` of an HTTP request; 429 `rate_limited` once over its limit."""
        if not self.allow(action, client):
            raise HTTPException(429, {"code": "rate_limited", "message": REFUSALS[action]})
