"""What routes depend on, as `Annotated` aliases: a route names `Registry` or `Store` in its
signature instead of reaching into `request.app.state`, so its needs are visible and a test
can override them (`app.dependency_overrides`). This module alone reads `app.state` (which
`server.app` fills).

They are `async def` although they only read `app.state`: FastAPI runs a plain `def`
dependency in a worker thread, and that hand-over (and the GIL's, back) took a third of the
event loop's time per WebSocket connection under a reconnect flood (docs/performance.md)."""

from __future__ import annotations

from typing import Annotated

from fastapi import Depends
from starlette.requests import HTTPConnection

from server.accounts import Accounts, Ceremonies, SignInLimits
from server.cluster import Cluster
from server.config import Settings
from server.ladder import PlayerData, PlayNow, RankedTables
from server.rooms import RoomRegistry
from server.store import Database

from .identity import SESSION_COOKIE, cookie_secret
from .owner import RoomAt, base_url
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


SettingsDep = Annotated[Settings, Depends(get_settings)]
Registry = Annotated[RoomRegistry, Depends(get_registry)]
Store = Annotated[Database, Depends(get_store)]
Quotas = Annotated[ClientQuotas, Depends(get_quotas)]
ClusterDep = Annotated[Cluster | None, Depends(get_cluster)]
ClientId = Annotated[str, Depends(client_id)]


async def get_players(conn: HTTPConnection) -> PlayerData:
    """The players' records (profiles, ratings, ranked results)."""
    data: PlayerData = conn.app.state.players
    return data


async def get_matchmaker(conn: HTTPConnection) -> PlayNow:
    """The Play now queue: in this process, or in Redis in cluster mode."""
    matchmaker: PlayNow = conn.app.state.matchmaker
    return matchmaker


async def get_ranked_tables(conn: HTTPConnection) -> RankedTables:
    tables: RankedTables = conn.app.state.ranked_tables
    return tables


async def get_accounts(conn: HTTPConnection) -> Accounts:
    accounts: Accounts = conn.app.state.accounts
    return accounts


async def get_ceremonies(conn: HTTPConnection) -> Ceremonies:
    ceremonies: Ceremonies = conn.app.state.ceremonies
    return ceremonies


async def get_sign_in_limits(conn: HTTPConnection) -> SignInLimits:
    limits: SignInLimits = conn.app.state.sign_in_limits
    return limits


AccountsDep = Annotated[Accounts, Depends(get_accounts)]
CeremoniesDep = Annotated[Ceremonies, Depends(get_ceremonies)]
SignInLimitsDep = Annotated[SignInLimits, Depends(get_sign_in_limits)]


async def get_session(
    conn: HTTPConnection, accounts: AccountsDep, registry: Registry
) -> str | None:
    """The asking device's session id (the `pool_session` cookie), if it is live. Only a
    request carrying that cookie asks the store: a guest's costs nothing more."""
    session = cookie_secret(conn, SESSION_COOKIE)
    if session is None or await accounts.session_player(session, registry.clock.wall()) is None:
        return None
    return session


Session = Annotated[str | None, Depends(get_session)]


async def get_secret(conn: HTTPConnection, session: Session) -> str | None:
    """What names the asking player: the live session of a signed-in account, else the
    guest's secret (the `pool_player` cookie), if any."""
    return session if session is not None else cookie_secret(conn)


async def get_base_url(conn: HTTPConnection, settings: SettingsDep, cluster: ClusterDep) -> str:
    """This process's address as clients reach it (for `ws_url`)."""
    return base_url(settings, cluster, str(conn.base_url))


async def get_room(room_id: str, registry: Registry, cluster: ClusterDep) -> RoomAt:
    """The path's `room_id`, wherever it is played (`RoomAt`: its owner's answer in cluster
    mode, else the room here or 404 `unknown_room`)."""
    return RoomAt(room_id, registry, cluster)


RoomDep = Annotated[RoomAt, Depends(get_room)]
Players = Annotated[PlayerData, Depends(get_players)]
Matchmaking = Annotated[PlayNow, Depends(get_matchmaker)]
RankedTablesDep = Annotated[RankedTables, Depends(get_ranked_tables)]
Secret = Annotated[str | None, Depends(get_secret)]
BaseUrl = Annotated[str, Depends(get_base_url)]
