"""Forwarding to the owning process: room requests that must run where the room is played
(open, show, join, a hint), and the path's room as routes see it (`RoomAt`).

One process: they run here. Cluster mode: a new room goes to the least loaded live process,
and showing or joining a room runs on its owner (the holder of its lease), called through
Redis; seats are taken by the owner alone, so two joins racing through two processes for
the last seat seat exactly one. Every answer carries `ws_url`: where to connect for the
room now.
"""

from __future__ import annotations

import asyncio
import logging
from dataclasses import dataclass
from typing import Any

from fastapi import HTTPException

from server.cluster import Cluster, Unreachable, ws_url
from server.config import Settings
from server.players import seat_token
from server.rooms import ActionError, LiveRoom, RoomRegistry
from server.rules import PRACTICE_KINDS

from .hints import hint_ask, hint_for
from .schemas import CreateRoom

log = logging.getLogger(__name__)
UNKNOWN_ROOM = {"code": "unknown_room", "message": "No such room."}
MOVING = {"code": "room_moving", "message": "The room is moving to another server; try again."}
UNAVAILABLE = {"code": "unavailable", "message": "Tables cannot be opened now; try again soon."}
CLOSE_UNAVAILABLE = 1013  # try again later


def base_url(settings: Settings, cluster: Cluster | None, request_base: str) -> str:
    """This process's address as clients reach it."""
    if cluster is not None:
        return cluster.url
    return (settings.public_url or request_base).rstrip("/")


async def open_room(
    registry: RoomRegistry,
    cluster: Cluster | None,
    body: CreateRoom,
    client: str,
    base: str,
) -> dict[str, Any]:
    """Create the room here (limits already checked by the receiving process)."""
    try:
        if body.opponent is not None and body.game in PRACTICE_KINDS:
            raise HTTPException(
                422, {"code": "bad_opponent", "message": "Practice is played alone."}
            )
        live = registry.create(
            body.game,
            body.race_to,
            body.shot_clock,
            body.listed,
            owner=client,
            opponent=body.opponent,
        )
    except ActionError as exc:
        code = 429 if exc.code == "too_many_rooms_open" else 503
        raise HTTPException(code, {"code": exc.code, "message": exc.message}) from None
    if cluster is not None:
        try:
            await asyncio.shield(cluster.own_new(live))
        except Exception:  # Redis or the store out of reach: no room half-opened
            log.exception("room %s could not be opened in the cluster", live.room.room_id)
            registry.forget(live.room.room_id)
            live.close(CLOSE_UNAVAILABLE, "server_unavailable")
            raise HTTPException(503, UNAVAILABLE) from None
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
        "ws_url": ws_url(base, room.room_id),
    }


def show(live: LiveRoom, base: str) -> dict[str, Any]:
    state = live.state_message().model_dump(mode="json", exclude={"type", "seq"})
    return {**live.room.summary(), "state": state, "ws_url": ws_url(base, live.room.room_id)}


def join(live: LiveRoom, name: str, base: str, key: str | None = None) -> dict[str, Any]:
    """Take a seat. `key`: the asking player's seat key (`server.players.seat_key`): a
    player already seated here gets the same seat and token back (another tab), else sits
    down with their own token; without one, a new random token."""
    room_id = live.room.room_id
    token = None if key is None else seat_token(key, room_id)
    seat = None if token is None else live.room.seat_of(token)
    if seat is None or token is None:
        try:
            seat, token = live.room.join(name, token=token)
        except ActionError as exc:
            code = 409 if exc.code == "room_full" else 422
            raise HTTPException(code, {"code": exc.code, "message": exc.message}) from None
        live.on_joined()
    return {
        "room_id": room_id,
        "seat": seat,
        "token": token,
        "name": live.room.name_of(seat),
        "ws_url": ws_url(base, room_id),
    }


async def forward(
    cluster: Cluster, node: str, op: str, args: dict[str, Any], timeout: float | None = None
) -> dict[str, Any]:
    """Run `op` on process `node`; its refusal is raised here as it was made there.
    `timeout`: for a call that takes longer than the cluster's usual one (a plan)."""
    try:
        reply = await cluster.inbox.call(node, op, args, timeout)
    except Unreachable:
        raise HTTPException(503, MOVING) from None
    if reply.status >= 400:
        raise HTTPException(reply.status, reply.body)
    return reply.body


async def room_owner(cluster: Cluster, room_id: str) -> str:
    """The process playing `room_id`: 404 when there is no such room, 503 while it moves
    (or while Redis cannot say)."""
    try:
        node = await cluster.owner(room_id)
        if node is not None:
            return node
        known = await cluster.directory.known(room_id)
    except Unreachable:
        raise HTTPException(503, MOVING) from None
    if known:
        raise HTTPException(503, MOVING)
    raise HTTPException(404, UNKNOWN_ROOM)


@dataclass(frozen=True)
class RoomAt:
    """The path's room, wherever it is played: a route first offers the request to the
    room's owner (`at_owner`), and when that is this process works on `live()`."""

    room_id: str
    registry: RoomRegistry
    cluster: Cluster | None

    def here(self) -> LiveRoom | None:
        return self.registry.get(self.room_id)

    async def at_owner(
        self, op: str, args: dict[str, Any], timeout: float | None = None
    ) -> dict[str, Any] | None:
        """Cluster mode, the room not played here: `op` run by its owner, and its answer
        (404 `unknown_room` when no process plays it, 503 while it moves). None: the
        request is for this process (the room is here, or there is one process)."""
        if self.cluster is None or self.here() is not None:
            return None
        node = await room_owner(self.cluster, self.room_id)
        return await forward(self.cluster, node, op, args, timeout)

    def live(self) -> LiveRoom:
        """The room played here, else 404 `unknown_room`."""
        live = self.here()
        if live is None:
            raise HTTPException(404, UNKNOWN_ROOM)
        return live


def answer_calls(cluster: Cluster, registry: RoomRegistry, settings: Settings) -> None:
    """Answer other processes' calls to open, show and join rooms here, and plan hints."""

    def local(room_id: str) -> LiveRoom:
        live = registry.get(room_id)
        if live is None:  # the lease says here, the room is not (yet, or any more)
            raise HTTPException(503, MOVING)
        return live

    async def answer(fn: Any, status: int = 200) -> tuple[int, dict[str, Any]]:
        try:
            return status, await fn()
        except HTTPException as exc:
            detail = exc.detail if isinstance(exc.detail, dict) else {"message": str(exc.detail)}
            return exc.status_code, detail

    async def create(args: dict[str, Any]) -> tuple[int, dict[str, Any]]:
        body = CreateRoom.model_validate(args["body"])
        return await answer(
            lambda: open_room(registry, cluster, body, args["client"], cluster.url), 201
        )

    async def show_here(args: dict[str, Any]) -> tuple[int, dict[str, Any]]:
        async def run() -> dict[str, Any]:
            return show(local(args["room_id"]), cluster.url)

        return await answer(run)

    async def join_here(args: dict[str, Any]) -> tuple[int, dict[str, Any]]:
        async def run() -> dict[str, Any]:
            return join(local(args["room_id"]), args["name"], cluster.url, args.get("key"))

        return await answer(run)

    async def hint_here(args: dict[str, Any]) -> tuple[int, dict[str, Any]]:
        ask = hint_ask(settings, args.get("client"), args.get("player"))
        return await answer(lambda: hint_for(local(args["room_id"]), args["token"], settings, ask))

    cluster.inbox.handlers.update(
        {"create": create, "show": show_here, "join": join_here, "hint": hint_here}
    )
