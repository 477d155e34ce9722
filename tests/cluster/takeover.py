"""The steps the failover and handover tests share: a 9-ball room (the rack of
`games.NINE_BALL`) opened and seated on a cluster, its break (a scratch) played and Ben's
cue ball placed, its sockets seen closing when the owner goes, and the room followed to the
process that takes it over."""

from __future__ import annotations

import asyncio
import time
from collections.abc import Iterable
from typing import Any, NamedTuple

from websockets.exceptions import ConnectionClosed

from tests.support.games import NINE_BALL_BREAK, NINE_BALL_PLACE, shoot_message

from .servers import Server
from .sockets import connect, place_cue, recv, send, until


class SeatedRoom(NamedTuple):
    """A room with Ana and Ben in its seats: what a test needs to play it."""

    room: str
    url: str  # the owner's `ws_url`
    ana: str  # seat 0's token
    ben: str  # seat 1's token


def seated(
    opened_through: Server, joined_through: Server | None = None, **room: object
) -> SeatedRoom:
    """A 9-ball room without a shot clock (and with `room`'s other options) opened through
    `opened_through`; Ana and Ben seated in it through `joined_through` (the same process
    unless given), both sent to the room's owner."""
    with opened_through.http() as one, (joined_through or opened_through).http() as two:
        created = one.post("/api/rooms", json={"game": "nine_ball", "shot_clock": 0, **room})
        assert created.status_code == 201, created.text
        room_id = created.json()["room_id"]
        ana = two.post(f"/api/rooms/{room_id}/join", json={"name": "Ana"}).json()
        ben = two.post(f"/api/rooms/{room_id}/join", json={"name": "Ben"}).json()
    assert (ana["seat"], ben["seat"]) == (0, 1)
    url = created.json()["ws_url"]
    assert ana["ws_url"] == ben["ws_url"] == url
    return SeatedRoom(room_id, url, ana["token"], ben["token"])


async def break_and_place(url: str, ana: str, ben: str) -> tuple[Any, Any, dict]:
    """Both players connected, the break (a scratch) and Ben's cue ball in hand placed: the
    sockets (Ana's, Ben's) and the state after the placing."""
    a, _, _ = await connect(url, ana)
    b, _, _ = await connect(url, ben)
    await send(a, shoot_message(NINE_BALL_BREAK))
    stream = await until(b, "state")
    result = next(m for m in stream if m["type"] == "shot_result")
    assert [f["code"] for f in result["outcome"]["fouls"]] == ["scratch"]
    placed = await place_cue(b, *NINE_BALL_PLACE)
    return a, b, placed


async def all_closed(sockets: Iterable[Any]) -> None:
    """Read every socket until the server closes it."""

    async def closed(ws: Any) -> None:
        try:
            while True:
                await recv(ws, 30)
        except ConnectionClosed:
            return

    await asyncio.gather(*(closed(ws) for ws in sockets))


def moved(server: Server, room: str, old_url: str, within: float) -> tuple[dict, float]:
    """Ask `server` about `room` until another process plays it: its answer and how long
    that took."""
    start = time.monotonic()
    with server.http() as client:
        while True:
            reply = client.get(f"/api/rooms/{room}")
            if reply.status_code == 200 and reply.json()["ws_url"] != old_url:
                return reply.json(), time.monotonic() - start
            assert reply.status_code in (200, 503), reply.text
            assert time.monotonic() - start < within, "the room was not taken over in time"
            time.sleep(0.1)
