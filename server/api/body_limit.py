"""Request bodies capped before anything parses them (`POOL_MAX_BODY_BYTES`).

Every body the API takes is a small JSON object; without a cap a 50 MB body was read whole
and parsed before its `422`, and two clients posting 20 MB bodies slowed every room's
stream. Pure ASGI middleware: a declared `Content-Length` over the cap is answered `413` at
once, before a byte of the body is read; a body without one (chunked) is counted as it
arrives and refused as soon as it passes the cap, the rest never read. The refusal closes
the connection, so the client's unsent remainder is not read either.
"""

from __future__ import annotations

from fastapi import HTTPException
from starlette.datastructures import Headers
from starlette.responses import JSONResponse
from starlette.types import ASGIApp, Message, Receive, Scope, Send

CODE = "body_too_large"


def too_large_detail(limit: int) -> dict[str, str]:
    return {"code": CODE, "message": f"A request body is at most {limit} bytes."}


class BodyTooLarge(HTTPException):
    """Raised into whoever reads a body past the cap; an `HTTPException`, so FastAPI's
    body reading passes it on and the app answers it as any other error."""

    def __init__(self, limit: int) -> None:
        super().__init__(413, too_large_detail(limit), headers={"connection": "close"})


def declared_length(scope: Scope) -> int | None:
    """The request's `Content-Length`, None when absent or not a number."""
    value = Headers(scope=scope).get("content-length")
    if value is None or not value.isdigit():
        return None
    return int(value)


class BodyLimit:
    """Refuse, with `413 body_too_large`, an HTTP request whose body exceeds `limit` bytes."""

    def __init__(self, app: ASGIApp, limit: int) -> None:
        self.app = app
        self.limit = limit

    async def __call__(self, scope: Scope, receive: Receive, send: Send) -> None:
        if scope["type"] != "http":
            await self.app(scope, receive, send)
            return
        declared = declared_length(scope)
        if declared is not None and declared > self.limit:
            await self._refuse(scope, receive, send)
            return
        received = 0
        started = False

        async def counted() -> Message:
            nonlocal received
            message = await receive()
            if message["type"] == "http.request":
                received += len(message.get("body", b""))
                if received > self.limit:
                    raise BodyTooLarge(self.limit)
            return message

        async def tracked(message: Message) -> None:
            nonlocal started
            started = started or message["type"] == "http.response.start"
            await send(message)

        try:
            await self.app(scope, counted, tracked)
        except BodyTooLarge:  # read outside a route (a middleware): answered here
            if started:
                raise
            await self._refuse(scope, receive, send)

    async def _refuse(self, scope: Scope, receive: Receive, send: Send) -> None:
        response = JSONResponse(
            {"detail": too_large_detail(self.limit)}, 413, headers={"connection": "close"}
        )
        await response(scope, receive, send)
