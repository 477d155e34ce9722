"""HTTP routes: health, limits, create/list/show rooms, take a seat."""

from __future__ import annotations

from typing import Annotated, Any

from fastapi import APIRouter, HTTPException, Query, status

from server.ai import LEVELS
from server.protocol import LIMITS, Limits
from server.rooms import ActionError

from .deps import ClientId, Quotas, Registry, RoomDep, SettingsDep
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
    body: CreateRoom, registry: Registry, settings: SettingsDep, quotas: Quotas, client: ClientId
) -> dict[str, Any]:
    """Open a table. `practice` has one seat and no clock; join it next to sit down.
    `listed: false` opens a private table: not in the lobby, joined through its link.
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
    try:
        if body.opponent is not None and body.game == "practice":
            raise HTTPException(
                422, {"code": "bad_opponent", "message": "Practice is played alone."}
            )
        live = registry.create(
            body.game, body.race_to, clock, body.listed, owner=client, opponent=body.opponent
        )
    except ActionError as exc:
        code = 429 if exc.code == "too_many_rooms_open" else 503
        raise HTTPException(code, {"code": exc.code, "message": exc.message}) from None
    room = live.room
    return {
        "room_id": room.room_id,
        "game": room.game,
        "race_to": room.race_to,
        "shot_clock": room.shot_clock,
        "seats": len(room.seats),
        "listed": room.listed,
        "opponent": next(iter(room.computer.values()), None),
        "url": f"/r/{room.room_id}",
    }


@router.get("/api/rooms", response_model=RoomList, tags=["rooms"])
async def list_rooms(
    registry: Registry,
    limit: Annotated[int, Query(ge=1, le=MAX_PAGE)] = 50,
    offset: Annotated[int, Query(ge=0, le=1_000_000)] = 0,
) -> dict[str, Any]:
    """Listed tables, newest first, a page at a time (`next`: the offset of the next page,
    null on the last); private tables are never listed."""
    listed = registry.listing()
    page = listed[offset : offset + limit]
    following = offset + limit if offset + limit < len(listed) else None
    return {
        "rooms": [live.room.summary() for live in page],
        "total": len(listed),
        "next": following,
    }


@router.get("/api/rooms/{room_id}", response_model=RoomDetail, responses=_ERRORS, tags=["rooms"])
async def show_room(live: RoomDep) -> dict[str, Any]:
    """The room and its full public state (the WebSocket `state` body)."""
    state = live.state_message().model_dump(mode="json", exclude={"type", "seq"})
    return {**live.room.summary(), "state": state}


@router.post("/api/rooms/{room_id}/join", response_model=Joined, responses=_ERRORS, tags=["rooms"])
async def join_room(
    room_id: str, body: JoinRoom, live: RoomDep, quotas: Quotas, client: ClientId
) -> dict[str, Any]:
    """Take the first free seat. The token is shown once; keep it to connect and reconnect.
    429: this client took too many seats within the rate window."""
    if not quotas.allow("join", client):
        raise HTTPException(
            429, {"code": "rate_limited", "message": "Too many seats taken; wait a minute."}
        )
    try:
        seat, token = live.room.join(body.name)
    except ActionError as exc:
        code = 409 if exc.code == "room_full" else 422
        raise HTTPException(code, {"code": exc.code, "message": exc.message}) from None
    live.on_joined(seat)
    return {"room_id": room_id, "seat": seat, "token": token, "name": live.room.name_of(seat)}


__all__ = ["RoomSummary", "router"]
