"""What routes depend on, as `Annotated` aliases: a route names `Registry` or `Store` in its
signature instead of reaching into `request.app.state`, so its needs are visible and a test
can override them (`app.dependency_overrides`).

They are `async def` although they only read `app.state`: FastAPI runs a plain `def`
dependency in a worker thread, and that hand-over (and the GIL's, back) took a third of the
event loop's time per WebSocket connection under a reconnect flood (docs/performance.md)."""

from __future__ import annotations

from typing import Annotated

from fastapi import Depends, HTTPException
from starlette.requests import HTTPConnection

from server.cluster import Cluster
from server.config import Settings
from server.rooms import LiveRoom, RoomRegistry
from server.store import Database

from .quotas import ClientQuotas


async def get_settings(conn: HTTPConnection) -> Settings:
    settings: Settings = conn.app.state.settings
    return settings


async def get_registry(conn: HTTPConnection) -> RoomRegistry:
    registry: RoomRegistry = conn.app.state.registry
    return registry


async def get_store(conn: HTTPConnection) -> Database:
    store: Database = conn.app.state.store
    return store


async def get_cluster(conn: HTTPConnection) -> Cluster | None:
    """This process's part in the cluster; None in one-process mode (no `POOL_REDIS_URL`)."""
    cluster: Cluster | None = getattr(conn.app.state, "cluster", None)
    return cluster


async def get_quotas(conn: HTTPConnection) -> ClientQuotas:
    quotas: ClientQuotas = conn.app.state.quotas
    return quotas


async def client_id(conn: HTTPConnection) -> str:
    """Who is asking, for per-client limits: the peer's address (no proxy headers are
    trusted)."""
    return conn.client.host if conn.client is not None else "unknown"


async def get_room(room_id: str, registry: Registry) -> LiveRoom:
    """The live room of the path's `room_id`, else 404 `unknown_room`."""
    live = registry.get(room_id)
    if live is None:
        raise HTTPException(404, {"code": "unknown_room", "message": "No such room."})
    return live


SettingsDep = Annotated[Settings, Depends(get_settings)]
Registry = Annotated[RoomRegistry, Depends(get_registry)]
Store = Annotated[Database, Depends(get_store)]
RoomDep = Annotated[LiveRoom, Depends(get_room)]
Quotas = Annotated[ClientQuotas, Depends(get_quotas)]
ClusterDep = Annotated[Cluster | None, Depends(get_cluster)]
ClientId = Annotated[str, Depends(client_id)]
