"""HTTP routes: health, limits, create/list/show rooms, take a seat."""

from __future__ import annotations

from typing import Annotated, Any

from fastapi import APIRouter, HTTPException, Query, Request, status

from server.ai import LEVELS
from server.cluster import Unreachable
from server.protocol import LIMITS, Limits

from . import routing
from .deps import ClientId, ClusterDep, Quotas, Registry, SettingsDep
from .hints import CALL_TIMEOUT, Hint, HintRequest, hint_for
from .identity import player_seat_key
from .players import remember_seat
from .ranked_friends import NEEDS_AGREEMENT, asking_player, check_create, seat_agreed, tables_of
from .schemas import (
    ComputerLevels,
    CreateRoom,
    ErrorResponse,
    Health,
    Joined,
    JoinRoom,
    RoomCreated,
    RoomDetail,
    RoomList,
    RoomSummary,
    ServerStats,
)

router = APIRouter()
MAX_PAGE = 100
_ERRORS: dict[int | str, dict[str, Any]] = {
    404: {"model": ErrorResponse},
    409: {"model": ErrorResponse},
    422: {"description": "Validation error"},
}


@router.get("/health", response_model=Health, tags=["meta"])
async def health() -> dict[str, Any]:
    return {"status": "ok"}


@router.get("/api/limits", response_model=Limits, tags=["meta"])
async def limits() -> Limits:
    """Every bound a client's messages must respect (also in each socket's `welcome`)."""
    return LIMITS


@router.get("/api/computer", response_model=ComputerLevels, tags=["meta"])
async def computer_levels() -> dict[str, Any]:
    """The levels the computer opponent plays at, weakest first (`opponent` of a new room)."""
    return {"levels": list(LEVELS)}


@router.get("/api/stats", response_model=ServerStats, tags=["meta"])
async def server_stats(
    registry: Registry, window: Annotated[float, Query(gt=0, le=600, allow_inf_nan=False)] = 60.0
) -> dict[str, Any]:
    """Load and stream health: rooms, connections, messages waiting in outboxes, and how
    late frames left the server (percentiles over the last `window` seconds)."""
    return registry.stats(window)


@router.post(
    "/api/rooms",
    status_code=status.HTTP_201_CREATED,
    response_model=RoomCreated,
    responses={
        422: {"description": "Validation error"},
        429: {"model": ErrorResponse},
        503: {"model": ErrorResponse},
    },
    tags=["rooms"],
)
async def create_room(
    body: CreateRoom,
    request: Request,
    registry: Registry,
    settings: SettingsDep,
    quotas: Quotas,
    client: ClientId,
    cluster: ClusterDep,
) -> dict[str, Any]:
    """Open a table. `practice` has one seat and no clock; join it next to sit down.
    `listed: false` opens a private table: not in the lobby, joined through its link.
    In cluster mode the table opens on the least loaded server (`ws_url` says which).
    `ranked: true` (with a profile): rated when both players agree on their joins.
    429: this client opened too many tables (at once, or within the rate window)."""
    if not quotas.allow("create", client):
        raise HTTPException(
            429, {"code": "rate_limited", "message": "Too many new tables; wait a minute."}
        )
    clock = body.shot_clock
    if clock is not None and 0 < clock < settings.min_shot_clock:
        raise HTTPException(
            422,
            {
                "code": "bad_shot_clock",
                "message": f"The shot clock is 0 (off) or at least "
                f"{settings.min_shot_clock:g} seconds.",
            },
        )
    if clock is not None and clock > settings.max_shot_clock:
        raise HTTPException(
            422,
            {
                "code": "bad_shot_clock",
                "message": f"The shot clock is at most {settings.max_shot_clock:g} seconds.",
            },
        )
    if body.ranked:
        check_create(body.game, body.opponent, cluster, await asking_player(request))
    if cluster is not None:
        node = await cluster.place()
        if node != cluster.node:
            args = {"body": body.model_dump(mode="json"), "client": client}
            return await routing.forward(cluster, node, "create", args)
    base = routing.base_url(settings, cluster, str(request.base_url))
    created = await routing.open_room(registry, settings, cluster, body, client, base)
    if body.ranked:
        tables_of(request).add(created["room_id"], body.game, set(registry.rooms))
    return {**created, "ranked": body.ranked}


@router.get("/api/rooms", response_model=RoomList, tags=["rooms"])
async def list_rooms(
    request: Request,
    registry: Registry,
    cluster: ClusterDep,
    limit: Annotated[int, Query(ge=1, le=MAX_PAGE)] = 50,
    offset: Annotated[int, Query(ge=0, le=1_000_000)] = 0,
) -> dict[str, Any]:
    """Listed tables (of every server, in cluster mode), newest first, a page at a time
    (`next`: the offset of the next page, null on the last); private tables are never
    listed."""
    try:
        rooms, total = (
            await cluster.directory.listing(offset, limit) if cluster is not None else ([], -1)
        )
    except Unreachable:  # Redis out of reach: this server's own tables, until it is back
        rooms, total = [], -1
    if total < 0:
        listed = registry.listing()
        rooms, total = (
            [
                {**live.room.summary(), "ranked": tables_of(request).is_ranked(live.room.room_id)}
                for live in listed[offset : offset + limit]
            ],
            len(listed),
        )
    following = offset + limit if offset + limit < total else None
    return {"rooms": rooms, "total": total, "next": following}


@router.get("/api/rooms/{room_id}", response_model=RoomDetail, responses=_ERRORS, tags=["rooms"])
async def show_room(
    room_id: str, request: Request, registry: Registry, settings: SettingsDep, cluster: ClusterDep
) -> dict[str, Any]:
    """The room, its full public state (the WebSocket `state` body) and `ws_url`."""
    live = registry.get(room_id)
    if live is None and cluster is not None:
        node = await routing.room_owner(cluster, room_id)
        return await routing.forward(cluster, node, "show", {"room_id": room_id})
    if live is None:
        raise HTTPException(404, {"code": "unknown_room", "message": "No such room."})
    shown = routing.show(live, routing.base_url(settings, cluster, str(request.base_url)))
    return {**shown, "ranked": tables_of(request).is_ranked(room_id)}


@router.post("/api/rooms/{room_id}/join", response_model=Joined, responses=_ERRORS, tags=["rooms"])
async def join_room(
    room_id: str,
    body: JoinRoom,
    request: Request,
    registry: Registry,
    settings: SettingsDep,
    quotas: Quotas,
    client: ClientId,
    cluster: ClusterDep,
) -> dict[str, Any]:
    """Take the first free seat. The token is shown once; keep it to connect and reconnect
    (at `ws_url`). A player with a profile (its cookie) sitting here already gets the same
    seat and token back. A ranked table needs `ranked: true` (the player's agreement) and a
    profile, else 409 `ranked_needs_agreement` and nobody is seated. 429: this client took
    too many seats within the rate window."""
    if not quotas.allow("join", client):
        raise HTTPException(
            429, {"code": "rate_limited", "message": "Too many seats taken; wait a minute."}
        )
    key = player_seat_key(request)  # a player with a profile sits with their own token
    live = registry.get(room_id)
    if live is None and cluster is not None:
        node = await routing.room_owner(cluster, room_id)
        args = {"room_id": room_id, "name": body.name, "key": key}
        joined = await routing.forward(cluster, node, "join", args)
        remember_seat(request, room_id, joined["seat"])
        return joined
    agreed = None
    if live is not None and tables_of(request).is_ranked(room_id):
        agreed = await asking_player(request) if body.ranked else None
        if agreed is None:  # no agreement (or no profile): nobody is seated
            raise HTTPException(409, NEEDS_AGREEMENT)
        live = registry.get(room_id)  # as it is after the wait
    if live is None:
        raise HTTPException(404, {"code": "unknown_room", "message": "No such room."})
    base = routing.base_url(settings, cluster, str(request.base_url))
    joined = routing.join(live, body.name, base, key)
    if agreed is not None:
        seat_agreed(request, live, joined["seat"], agreed)
    remember_seat(request, room_id, joined["seat"])
    return joined


@router.post(
    "/api/rooms/{room_id}/hint",
    response_model=Hint,
    responses={**_ERRORS, 403: {"model": ErrorResponse}, 429: {"model": ErrorResponse}},
    tags=["rooms"],
)
async def hint(
    room_id: str, body: HintRequest, registry: Registry, settings: SettingsDep, cluster: ClusterDep
) -> dict[str, Any]:
    """Practice: "Show me a shot". The strongest computer level plans the player's shot
    (off the event loop, on the server that plays the table) and the plan comes back
    without being played. 403 for a token that is not this table's, 409 when the table is
    not practice or not at rest for the player, 429 while a hint for the table is being
    planned."""
    live = registry.get(room_id)
    if live is None and cluster is not None:
        node = await routing.room_owner(cluster, room_id)
        args = {"room_id": room_id, "token": body.token}
        return await routing.forward(cluster, node, "hint", args, timeout=CALL_TIMEOUT)
    if live is None:
        raise HTTPException(404, {"code": "unknown_room", "message": "No such room."})
    return await hint_for(live, body.token, settings.computer_workers, settings.computer_starved)


__all__ = ["RoomSummary", "router"]
