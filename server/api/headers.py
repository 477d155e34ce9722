"""Security headers on every HTTP response: the page runs only its own scripts and styles,
cannot be framed, and sends no referrer off-site."""

from __future__ import annotations

import functools
from collections.abc import Callable, Iterable

from starlette.types import ASGIApp, Message, Receive, Scope, Send

CONTENT_SECURITY_POLICY = (
    "default-src 'self'; script-src 'self'; style-src 'self'; img-src 'self' data: blob:; "
    "connect-src 'self'; media-src 'self' blob:; object-src 'none'; base-uri 'none'; "
    "form-action 'self'; frame-ancestors 'none'"
)
HEADERS: list[tuple[bytes, bytes]] = [
    (b"content-security-policy", CONTENT_SECURITY_POLICY.encode()),
    (b"x-content-type-options", b"nosniff"),
    (b"referrer-policy", b"same-origin"),
    (b"x-frame-options", b"DENY"),
    (b"cross-origin-opener-policy", b"same-origin"),
]


def headers_with(connect: Iterable[str]) -> list[tuple[bytes, bytes]]:
    """`HEADERS`, the page also allowed to open sockets to `connect` (configured origins,
    the other servers of a cluster: a room's `ws_url` may be on any of them)."""
    return _headers_for(tuple(sorted(set(connect))))


@functools.lru_cache(maxsize=32)
def _headers_for(origins: tuple[str, ...]) -> list[tuple[bytes, bytes]]:
    """Built once per set of origins (asked at every response, it rarely changes)."""
    if not origins:
        return HEADERS
    extra = " ".join(origins)
    policy = CONTENT_SECURITY_POLICY.replace("connect-src 'self'", f"connect-src 'self' {extra}")
    return [(b"content-security-policy", policy.encode()), *HEADERS[1:]]


class SecurityHeaders:
    """Pure ASGI middleware (no per-request task, unlike `BaseHTTPMiddleware`).
    `connect`: more WebSocket origins the page may connect to, asked at each response."""

    def __init__(self, app: ASGIApp, connect: Callable[[], Iterable[str]] | None = None) -> None:
        self.app = app
        self.connect = connect

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return

        headers = HEADERS if self.connect is None else headers_with(self.connect())

        async def send_with_headers(message: Message) -> None:
            if message["type"] == "http.response.start":
                message["headers"] = [*message.get("headers", ()), *headers]
            await send(message)

        await self.app(scope, receive, send_with_headers)
