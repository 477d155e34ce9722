"""Per-client limits on what costs the server: opening rooms, taking seats, opening
spectator sockets. A client is
its address; the limits come from settings in the `limits` library's notation
("30/minute"), counted in a moving window, so one script cannot take every room or seat."""

from __future__ import annotations

from limits import RateLimitItem, parse
from limits.storage import MemoryStorage
from limits.strategies import MovingWindowRateLimiter

from server.config import Settings


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
