"""Per-client limits on what costs the server: opening rooms and taking seats. A client is
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
        }

    def allow(self, action: str, client: str) -> bool:
        """Count one `action` ("create" or "join") by `client`; False once over its limit."""
        return self._limiter.hit(self._items[action], action, client)
