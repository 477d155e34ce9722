"""The room WebSocket: handshake checks, then one reader and one sender per connection.

Everything is checked before `accept()` (Origin, room, token, the address's quota of
spectator sockets: close 1008). After that the reader validates each raw text frame (size,
rate, JSON, schema) and hands it to the room; the sender drains the connection's bounded
outbox. Either ending ends both.
"""

from __future__ import annotations

import asyncio
import contextlib
import logging

from fastapi import APIRouter, WebSocket
from starlette.websockets import WebSocketState

from server.config import Settings
from server.protocol import BadMessage, parse_client_message
from server.protocol.outbound import ErrorMessage, text
from server.rooms import LiveRoom
from server.rooms.connection import Connection, cancel_quietly
from server.rooms.ratelimit import TokenBucket

from .deps import ClientId, ClusterDep, Quotas, Registry, SettingsDep
from .origin import socket_allowed

router = APIRouter()
log = logging.getLogger(__name__)

CLOSE_POLICY = 1008
CLOSE_TOO_BIG = 1009


@router.websocket("/ws/rooms/{room_id}")
async def room_socket(
    websocket: WebSocket,
    room_id: str,
    settings: SettingsDep,
    registry: Registry,
    cluster: ClusterDep,
    quotas: Quotas,
    client: ClientId,
    token: str | None = None,
) -> None:
    if not await socket_allowed(websocket, settings, cluster):
        await websocket.close(CLOSE_POLICY, "origin_not_allowed")
        return
    live = registry.get(room_id)
    if live is None:
        # Another server plays it (or will in a moment): GET /api/rooms/{id} says where.
        reason = "room_moved" if cluster is not None else "unknown_room"
        await websocket.close(CLOSE_POLICY, reason)
        return
    seat = None
    if token is not None:
        seat = live.room.seat_of(token)
        if seat is None:
            await websocket.close(CLOSE_POLICY, "bad_token")
            return
    elif not quotas.allow("watch", client):
        await asyncio.sleep(settings.watch_refusal_delay)
        await websocket.close(CLOSE_POLICY, "too_many_connections")
        return
    await websocket.accept()
    if seat is None and live.room.spectators >= settings.max_spectators:
        await websocket.close(CLOSE_POLICY, "room_crowded")
        return
    conn = Connection(
        websocket.send_text,
        seat,
        live.room.name_of(seat) if seat is not None else None,
        limit=settings.send_queue,
        send_timeout=settings.send_timeout,
        chat_credit=chat_credit(settings, spectator=seat is None),
        send_bytes=websocket.send_bytes,
    )
    live.attach(conn)
    sender = asyncio.create_task(conn.run_sender())
    reader = asyncio.create_task(_read(websocket, live, conn, settings))
    try:
        await asyncio.wait({sender, reader}, return_when=asyncio.FIRST_COMPLETED)
        if conn.flushing and not sender.done():  # the replies owed before the close
            await asyncio.wait({sender}, timeout=settings.send_timeout)
    finally:
        await cancel_quietly(reader)
        await cancel_quietly(sender)
        live.detach(conn)
        if conn.close_code is not None and websocket.client_state == WebSocketState.CONNECTED:
            with contextlib.suppress(Exception):
                await asyncio.wait_for(
                    websocket.close(conn.close_code, conn.close_reason), settings.send_timeout
                )


def chat_credit(settings: Settings, spectator: bool) -> TokenBucket:
    if spectator:
        return TokenBucket(settings.spectator_chat_burst, settings.spectator_chat_per_second)
    return TokenBucket(settings.player_chat_burst, settings.player_chat_per_second)


async def _read(websocket: WebSocket, live: LiveRoom, conn: Connection, settings: Settings) -> None:
    """Read raw frames until the peer leaves or breaks a limit (then `conn.close_code`)."""
    bucket = (
        TokenBucket(settings.rate_burst, settings.rate_per_second)
        if conn.seat is not None
        else TokenBucket(settings.spectator_rate_burst, settings.spectator_rate_per_second)
    )
    while True:
        message = await websocket.receive()
        if message["type"] == "websocket.disconnect":
            return
        raw = message.get("text")
        if raw is None:
            size = len(message.get("bytes") or b"")
        else:
            size = (
                len(raw.encode("utf-8", "surrogatepass"))
                if len(raw) * 4 > settings.max_message
                else len(raw)
            )
        if size > settings.max_message:
            conn.close(CLOSE_TOO_BIG, "message_too_big")
            return
        if not bucket.take():
            conn.close(CLOSE_POLICY, "rate_limited", flush=True)
            return
        if raw is None:
            conn.push(
                text(ErrorMessage(code="binary_not_supported", message="Send JSON text frames."))
            )
            continue
        try:
            msg = parse_client_message(raw)
        except BadMessage as exc:
            conn.push(text(ErrorMessage(code=exc.code, message=exc.message, ref=exc.ref)))
            continue
        live.handle(conn, msg)
