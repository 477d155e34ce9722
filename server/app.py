"""The FastAPI application: HTTP API, the room WebSocket, and the web client from `web/`."""

from __future__ import annotations

import asyncio
import contextlib
from collections.abc import AsyncIterator
from pathlib import Path

from fastapi import FastAPI, HTTPException
from fastapi.responses import FileResponse
from fastapi.staticfiles import StaticFiles

from server.api.http import router as http_router
from server.api.ws import router as ws_router
from server.config import Settings
from server.rooms import RoomRegistry
from server.rooms.observer import RoomObserver

CLOSE_RESTART = 1012


def create_app(settings: Settings | None = None,
               observer: RoomObserver | None = None) -> FastAPI:
    """Build the app. `settings` defaults to `Settings.from_env()`; `observer` is the store
    hook (issue 7) told about every shot and room change."""
    settings = settings or Settings.from_env()
    registry = RoomRegistry(settings, observer)

    @contextlib.asynccontextmanager
    async def lifespan(app: FastAPI) -> AsyncIterator[None]:
        sweeper = asyncio.create_task(registry.run_sweeper())
        try:
            yield
        finally:
            sweeper.cancel()
            with contextlib.suppress(asyncio.CancelledError):
                await sweeper
            registry.close_all(CLOSE_RESTART, "server_restart")
            await asyncio.sleep(0)  # let the senders see the close

    app = FastAPI(title="Pool online", version="1.0",
                  description="Rooms, seats and the authoritative game stream. "
                              "The WebSocket protocol is in docs/protocol.md.",
                  lifespan=lifespan)
    app.state.settings = settings
    app.state.registry = registry
    app.include_router(http_router)
    app.include_router(ws_router)
    _serve_web(app, settings.web_dir)
    return app


def _serve_web(app: FastAPI, web_dir: Path) -> None:
    """`/` and the static files from `web/`; `/r/{room_id}` is the same page (room links)."""
    index = web_dir / "index.html"

    @app.get("/r/{room_id}", include_in_schema=False)
    async def room_page(room_id: str) -> FileResponse:
        if not index.is_file():
            raise HTTPException(404, {"code": "no_client", "message": "web/ is missing."})
        return FileResponse(index, media_type="text/html")

    app.mount("/", StaticFiles(directory=web_dir, html=True, check_dir=False), name="web")
