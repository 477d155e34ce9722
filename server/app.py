"""The FastAPI application: HTTP API, the room WebSocket, and the web client from `web/`."""

from __future__ import annotations

import asyncio
import contextlib
from collections.abc import AsyncIterator, Callable, Iterable
from dataclasses import dataclass
from pathlib import Path

from fastapi import FastAPI, HTTPException
from fastapi.exceptions import RequestValidationError
from fastapi.responses import FileResponse
from fastapi.staticfiles import StaticFiles

from server.accounts import Accounts, Ceremonies, SignInLimits
from server.api.accounts import router as accounts_router
from server.api.analysis import router as analysis_router
from server.api.body_limit import BodyLimit
from server.api.drills import router as drills_router
from server.api.headers import SecurityHeaders
from server.api.matches import router as matches_router
from server.api.meta import router as meta_router
from server.api.name_errors import validation_handler
from server.api.owner import answer_calls
from server.api.passkeys import router as passkeys_router
from server.api.players import router as players_router
from server.api.quotas import ClientQuotas
from server.api.rooms import router as rooms_router
from server.api.unavailable import store_unavailable_handler
from server.api.ws import router as ws_router
from server.cluster import Cluster
from server.config import Settings
from server.ladder import (
    ClusterMatchmaker,
    GuestPruning,
    Matchmaker,
    PlayerData,
    PlayNow,
    RankedResults,
    RankedTables,
)
from server.players import Window
from server.rooms import Clock, RoomRegistry, SeedSource, StoreObserver
from server.rooms.analyses import AnalysisQueue
from server.rooms.clock import SYSTEM_CLOCK
from server.rooms.computer import close_planners, open_planners
from server.rooms.observer import RoomObserver
from server.store import Database, StoreUnavailable

CLOSE_RESTART = 1012


def create_app(
    settings: Settings | None = None,
    observer: RoomObserver | None = None,
    store: Database | None = None,
    clock: Clock = SYSTEM_CLOCK,
    seeds: SeedSource | None = None,
) -> FastAPI:
    """Build the app. `settings` defaults to `Settings.from_env()`. `store` is the
    history and room store (default: `settings.database`, PostgreSQL or SQLite); its
    `StoreObserver` is told about every shot and room change unless `observer` is given.
    `clock` and `seeds` (the rack seeds of new rooms) are for tests that need a fixed game.
    The lifespan restores the saved rooms on start and keeps them on shutdown."""
    settings = settings or Settings.from_env()
    store = store or Database(settings.database)
    if observer is None:
        observer = StoreObserver(store)
    if seeds is None and settings.rack_seed is not None:
        seeds = SeedSource.fixed(settings.rack_seed)
    registry = RoomRegistry(settings, observer, clock=clock, seeds=seeds)
    # Cluster mode: rooms are shared out among the processes; on start this one takes only
    # rooms whose owner is gone, and on shutdown it hands its own over (docs/scaling.md).
    cluster = Cluster(settings, registry, store) if settings.redis_url is not None else None
    if cluster is not None and isinstance(observer, StoreObserver):
        observer.use_cluster(cluster.match_ids, cluster.epoch_of, cluster.stale)
    players = PlayerData(store)
    results = RankedResults(
        registry, players, observer.match_id if isinstance(observer, StoreObserver) else None
    )
    matchmaker = pick_matchmaker(registry, results, cluster)
    analyses = AnalysisQueue(store, settings)
    guests = GuestPruning(
        players, matchmaker, clock, settings.guest_ttl, settings.guest_prune_every
    )
    lifespan = _Lifespan(registry, store, observer, cluster, matchmaker, analyses, guests)
    app = FastAPI(
        title="Pool online",
        version="1.0",
        description="Rooms, seats and the authoritative game stream. "
        "The WebSocket protocol is in docs/protocol.md.",
        lifespan=lifespan,
        docs_url=None,  # the interactive docs load scripts from a CDN; the schema stays
        redoc_url=None,
    )
    app.add_middleware(BodyLimit, limit=settings.max_body_bytes)
    app.add_middleware(SecurityHeaders, connect=page_sockets(settings, cluster))
    app.state.settings = settings
    app.state.registry = registry
    app.state.quotas = ClientQuotas(settings)
    app.state.store = store
    app.state.cluster = cluster
    app.state.players = players
    app.state.matchmaker = matchmaker
    app.state.analyses = analyses
    app.state.guests = guests
    app.state.ranked_tables = RankedTables(results)
    app.state.accounts = Accounts(store, settings.session_idle)
    app.state.ceremonies = Ceremonies(store)
    app.state.sign_in_limits = SignInLimits(settings.login_rate, settings.login_account_rate)
    if cluster is not None:
        answer_calls(cluster, registry, settings)
    for router in (
        *(meta_router, rooms_router, matches_router, analysis_router, ws_router),
        *(drills_router, players_router, accounts_router, passkeys_router),
    ):
        app.include_router(router)
    app.add_exception_handler(RequestValidationError, validation_handler)
    app.add_exception_handler(StoreUnavailable, store_unavailable_handler)
    _serve_web(app, settings.web_dir)
    return app


@dataclass
class _Lifespan:
    """What the app starts and stops around serving: the shot runner, the planners, the
    store, the saved rooms (or the cluster's share of them), Play now, the analyses, guest
    pruning and the sweepers."""

    registry: RoomRegistry
    store: Database
    observer: RoomObserver
    cluster: Cluster | None
    matchmaker: PlayNow
    analyses: AnalysisQueue
    guests: GuestPruning

    @contextlib.asynccontextmanager
    async def __call__(self, app: FastAPI) -> AsyncIterator[None]:  # noqa: ARG002 (FastAPI's signature)
        await self._start()
        background = [
            asyncio.create_task(self.registry.run_sweeper()),
            asyncio.create_task(self.registry.run_watchdog()),
            asyncio.create_task(self.matchmaker.run()),
            asyncio.create_task(self.guests.run()),
        ]
        try:
            yield
        finally:
            for task in background:
                task.cancel()
                with contextlib.suppress(asyncio.CancelledError):
                    await task
            await self._stop()

    async def _start(self) -> None:
        registry, store, observer = self.registry, self.store, self.observer
        await registry.runner.start()
        open_planners()
        store.open()
        if isinstance(observer, StoreObserver):
            observer.start()
        if self.cluster is not None:
            await self.cluster.start()
        elif isinstance(observer, StoreObserver):
            registry.restore(await store.call(lambda repo: repo.rooms()))
        await self.matchmaker.resume()
        self.analyses.kick()  # analyses queued before this start, or left by a process gone

    async def _stop(self) -> None:
        registry, store = self.registry, self.store
        if isinstance(self.observer, StoreObserver):
            self.observer.stop()  # the saved rooms stay saved for the next start
        await self.analyses.close()
        registry.close_all(CLOSE_RESTART, "server_restart")
        await asyncio.sleep(0)  # let the senders see the close
        if self.cluster is not None:
            await store.call(lambda _repo: None, wait=True)  # every room's last write is stored
            with contextlib.suppress(Exception):  # Redis gone: leases simply expire
                await self.cluster.drain()
            await self.cluster.stop()
        await asyncio.to_thread(store.close)  # every queued write is on disk
        registry.runner.close()
        await asyncio.to_thread(close_planners)


def pick_matchmaker(
    registry: RoomRegistry, results: RankedResults, cluster: Cluster | None
) -> PlayNow:
    """The Play now queue: in this process, or in Redis in cluster mode. The lifespan
    starts its `run` and calls its `resume` after the rooms are restored."""
    settings = registry.settings
    window = Window(
        settings.playnow_window,
        settings.playnow_widen,
        settings.playnow_window_max,
        settings.playnow_computer_after,
    )
    if cluster is None:
        return Matchmaker(registry, results, window)
    return ClusterMatchmaker(registry, results, window, cluster)


def page_sockets(settings: Settings, cluster: Cluster | None) -> Callable[[], Iterable[str]] | None:
    """What the page may open sockets to besides its own server, asked at each response:
    the configured `socket_origins` and the other live servers of a cluster."""
    configured = settings.socket_origins
    if cluster is None:
        return (lambda: configured) if configured else None
    return lambda: [*configured, *peer_sockets(cluster)]


def peer_sockets(cluster: Cluster) -> list[str]:
    """The WebSocket origins of the other live servers (a page may connect to them)."""
    return [
        url.replace("https://", "wss://", 1).replace("http://", "ws://", 1)
        for url in cluster.origins()[1:]
    ]


def _serve_web(app: FastAPI, web_dir: Path) -> None:
    """The client's own files only (the page, its stylesheet and `js/`; not its tests or
    package files). `/r/{room_id}` (a table), `/m/{match_id}` (a finished match,
    replayed), `/profile`, `/p/{player_id}`, `/leaderboard` and `/login` are the same page:
    the client routes on the path."""
    index = web_dir / "index.html"

    async def page() -> FileResponse:
        if not index.is_file():
            raise HTTPException(404, {"code": "no_client", "message": "web/ is missing."})
        return FileResponse(index, media_type="text/html")

    for path in (
        "/",
        "/r/{room_id}",
        "/m/{match_id}",
        "/profile",
        "/p/{player_id}",
        "/leaderboard",
        "/login",
    ):
        app.add_api_route(path, page, methods=["GET"], include_in_schema=False)

    @app.get("/style.css", include_in_schema=False)
    async def stylesheet() -> FileResponse:
        path = web_dir / "style.css"
        if not path.is_file():
            raise HTTPException(404, {"code": "not_found", "message": "No such file."})
        return FileResponse(path, media_type="text/css")

    app.mount("/js", StaticFiles(directory=web_dir / "js", check_dir=False), name="js")
