"""The answer to a request whose store read got no answer in time (PostgreSQL out of reach,
or busy with the writes queued before it): `503 unavailable`, never a hang or a 500."""

from __future__ import annotations

import logging

from fastapi import Request
from fastapi.responses import JSONResponse, Response

from server.store import StoreUnavailable

log = logging.getLogger(__name__)
UNAVAILABLE_STORE = {
    "code": "unavailable",
    "message": "The history cannot be reached just now; try again soon.",
}


async def store_unavailable_handler(request: Request, exc: Exception) -> Response:
    assert isinstance(exc, StoreUnavailable)
    log.warning("store: %s %s: %s", request.method, request.url.path, exc)
    return JSONResponse({"detail": UNAVAILABLE_STORE}, status_code=503)
