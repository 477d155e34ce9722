"""`ws_url`: where a client connects for a room now. In one process it is this server (its
`POOL_PUBLIC_URL`, else the address the request came to); in a cluster, the room's owner,
whichever server is asked, and a page served by any live server may connect there."""

from __future__ import annotations

import asyncio
import time
from pathlib import Path

import pytest
import websockets
from fastapi.testclient import TestClient

from tests.support.games import EIGHT_BALL
from tests.support.rooms import app_with
from tests.support.settings import settings_in

from .servers import ServerSet
from .sockets import connect

pytestmark = [pytest.mark.timeout(300), pytest.mark.redis, pytest.mark.postgres, pytest.mark.slow]


def test_one_process_names_itself(tmp_path: Path) -> None:
    with TestClient(app_with(settings_in(tmp_path))) as client:
        created = client.post("/api/rooms", json={"game": "eight_ball"}).json()
        room = created["room_id"]
        expected = f"ws://testserver/ws/rooms/{room}"
        assert created["ws_url"] == expected
        assert client.post(f"/api/rooms/{room}/join", json={"name": "Ana"}).json()["ws_url"] == (
            expected
        )
        assert client.get(f"/api/rooms/{room}").json()["ws_url"] == expected
        with client.websocket_connect(expected.removeprefix("ws://testserver")) as ws:
            assert ws.receive_json()["type"] == "welcome"


def test_one_process_behind_its_public_url(tmp_path: Path) -> None:
    settings = settings_in(tmp_path, public_url="https://pool.example")
    with TestClient(app_with(settings)) as client:
        created = client.post("/api/rooms", json={"game": "practice"}).json()
        assert created["ws_url"] == f"wss://pool.example/ws/rooms/{created['room_id']}"


def test_pages_of_every_server_may_connect_to_the_owner(servers) -> None:
    group: ServerSet = servers(2, store="sqlite", rack_seed=EIGHT_BALL)
    here, there = group.all
    with here.http() as client:
        rooms = [client.post("/api/rooms", json={"game": "practice"}).json() for _ in range(2)]
        elsewhere = next(r for r in rooms if there.address in r["ws_url"])
        room = elsewhere["room_id"]
        # asked here, the answer points there
        assert client.get(f"/api/rooms/{room}").json()["ws_url"] == elsewhere["ws_url"]
        # the page may open sockets to the other server (as soon as this one has seen it
        # announce itself: a heartbeat)
        deadline = time.monotonic() + 20
        while f"connect-src 'self' ws://{there.address};" not in (
            policy := client.get("/").headers["content-security-policy"]
        ):
            assert time.monotonic() < deadline, policy
            time.sleep(0.1)

    async def sockets() -> None:
        # a page of this server opens the room's socket on the other one
        ws, welcome, _ = await connect(elsewhere["ws_url"], None, origin=here.url)
        assert welcome["room_id"] == room
        await ws.close()
        with pytest.raises(websockets.InvalidStatus):  # a page of another site may not
            await websockets.connect(elsewhere["ws_url"], origin="http://evil.example")
        # the server that does not play the room sends the client to ask again
        with pytest.raises(websockets.InvalidStatus):
            await websockets.connect(f"ws://{here.address}/ws/rooms/{room}")

    asyncio.run(sockets())
