"""HTTP routes of rooms: open, list, show, take a seat, and practice's hint. A request
about one room runs on the process that plays it (`RoomDep`, `server.api.owner`)."""

from __future__ import annotations

from typing import Annotated, Any

from fastapi import APIRouter, HTTPException, Query, Request, status

from server.cluster import Unreachable
from server.players import seat_key

from . import owner
from .deps import (
    BaseUrl,
    ClientId,
    ClusterDep,
    Players,
    Quotas,
    RankedTablesDep,
    Registry,
    RoomDep,
    Secret,
    SettingsDep,
)
from .disconnect import unless_gone
from .hints import CALL_TIMEOUT, Hint, HintRequest, hint_ask, hint_for
from .players import remember_seat
from .ranked_friends import NEEDS_AGREEMENT, asking_player, check_create
from .schemas import (
    CreateRoom,
    ErrorResponse,
    Joined,
    JoinRoom,
    RoomCreated,
    RoomDetail,
    RoomList,
    RoomSummary,
)

router = APIRouter(tags=["rooms"])
MAX_PAGE = 100
NO_PROFILE_NAME = "Give a name to play under: this browser has no profile yet."
_ERRORS: dict[int | str, dict[str, Any]] = {
    404: {"model": ErrorResponse},
    409: {"model": ErrorResponse},
    422: {"description": "Validation error"},
}


@router.post(
    "/api/rooms",
    status_code=status.HTTP_201_CREATED,
    response_model=RoomCreated,
    responses={
        422: {"description": "Validation error"},
        429: {"model": ErrorResponse},
        503: {"model": ErrorResponse},
    },
)
async def create_room(
    body: CreateRoom,
    registry: Registry,
    settings: SettingsDep,
    quotas: Quotas,
    client: ClientId,
    cluster: ClusterDep,
    base: BaseUrl,
    tables: RankedTablesDep,
    data: Players,
    secret: Secret,
) -> dict[str, Any]:
    """Open a table. `practice` has one seat and no clock; join it next to sit down.
    `listed: false` opens a private table: not in the lobby, joined through its link.
    In cluster mode the table opens on the least loaded server (`ws_url` says which).
    `ranked: true` (with a profile): rated when both players agree on their joins.
    429: this client opened too many tables (at once, or within the rate window)."""
    quotas.enforce("create", client)
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
        check_create(body.game, body.opponent, cluster, await asking_player(secret, data))
    if cluster is not None:
        node = await cluster.place()
        if node != cluster.node:
            args = {"body": body.model_dump(mode="json"), "client": client}
            return await owner.forward(cluster, node, "create", args)
    created = await owner.open_room(registry, cluster, body, client, base)
    if body.ranked:
        tables.add(created["room_id"], body.game, set(registry.rooms))
    return {**created, "ranked": body.ranked}


@router.get("/api/rooms", response_model=RoomList)
async def list_rooms(
    registry: Registry,
    cluster: ClusterDep,
    tables: RankedTablesDep,
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
                {**live.room.summary(), "ranked": tables.is_ranked(live.room.room_id)}
                for live in listed[offset : offset + limit]
            ],
            len(listed),
        )
    following = offset + limit if offset + limit < total else None
    return {"rooms": rooms, "total": total, "next": following}


@router.get("/api/rooms/{room_id}", response_model=RoomDetail, responses=_ERRORS)
async def show_room(room: RoomDep, base: BaseUrl, tables: RankedTablesDep) -> dict[str, Any]:
    """The room, its full public state (the WebSocket `state` body) and `ws_url`."""
    elsewhere = await room.at_owner("show", {"room_id": room.room_id})
    if elsewhere is not None:
        return elsewhere
    shown = owner.show(room.live(), base)
    return {**shown, "ranked": tables.is_ranked(room.room_id)}


@router.post("/api/rooms/{room_id}/join", response_model=Joined, responses=_ERRORS)
async def join_room(
    room: RoomDep,
    body: JoinRoom,
    registry: Registry,
    quotas: Quotas,
    client: ClientId,
    base: BaseUrl,
    tables: RankedTablesDep,
    data: Players,
    secret: Secret,
) -> dict[str, Any]:
    """Take the first free seat. The token is shown once; keep it to connect and reconnect
    (at `ws_url`). A player with a profile (its cookie) sitting here already gets the same
    seat and token back. A ranked table needs `ranked: true` (the player's agreement) and a
    profile, else 409 `ranked_needs_agreement` and nobody is seated. 429: this client took
    too many seats within the rate window. Without `name` the player sits under their
    profile's name (422 `bad_name` without a profile)."""
    quotas.enforce("join", client)
    key = None if secret is None else seat_key(secret)  # a player sits with their own token
    room_id = room.room_id
    name = body.name if body.name is not None else await profile_name(secret, data)
    joined = await room.at_owner("join", {"room_id": room_id, "name": name, "key": key})
    if joined is not None:
        remember_seat(data, secret, room_id, joined["seat"], registry.clock.wall())
        return joined
    agreed = None
    if room.here() is not None and tables.is_ranked(room_id):
        agreed = await asking_player(secret, data) if body.ranked else None
        if agreed is None:  # no agreement (or no profile): nobody is seated
            raise HTTPException(409, NEEDS_AGREEMENT)
    live = room.live()  # as it is after the wait
    joined = owner.join(live, name, base, key)
    if agreed is not None:
        tables.seated(live, joined["seat"], agreed)
    remember_seat(data, secret, room_id, joined["seat"], registry.clock.wall())
    return joined


async def profile_name(secret: str | None, data: Players) -> str:
    """The name of the request's profile, for a join that gives none."""
    player = await asking_player(secret, data)
    if player is None:
        raise HTTPException(422, {"code": "bad_name", "message": NO_PROFILE_NAME})
    return player.name


@router.post(
    "/api/rooms/{room_id}/hint",
    response_model=Hint,
    responses={**_ERRORS, 403: {"model": ErrorResponse}, 429: {"model": ErrorResponse}},
)
async def hint(
    room: RoomDep,
    body: HintRequest,
    request: Request,
    settings: SettingsDep,
    client: ClientId,
    secret: Secret,
) -> dict[str, Any]:
    """Practice: "Show me a shot". The strongest computer level plans the player's shot
    (off the event loop, on the server that plays the table, after the rooms' computer
    turns) and the plan comes back without being played. 403 for a token that is not this
    table's, 409 when the table is not practice or not at rest for the player, 429
    `hint_pending` while this table, address or player has a hint asked, 429 `hints_busy`
    while the queue of hints is full, 503 `hint_timeout` when the planners stayed busy
    `POOL_HINT_WAIT` s. A hint whose client leaves before it starts is not planned."""
    player = None if secret is None else seat_key(secret)
    args = {"room_id": room.room_id, "token": body.token, "client": client, "player": player}
    elsewhere = await unless_gone(request, room.at_owner("hint", args, timeout=CALL_TIMEOUT))
    if elsewhere is not None:
        return elsewhere
    ask = hint_ask(settings, client, player)
    return await unless_gone(request, hint_for(room.live(), body.token, settings, ask))


__all__ = ["RoomSummary", "router"]
