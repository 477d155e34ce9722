"""A real uvicorn on a free port, real sockets, real-time pacing, the `websockets` client.

Covers what TestClient cannot: uvicorn's own 1009 on a big frame, the handshake refusal as
a browser sees it (HTTP 403), a player dropping mid-shot and reconnecting, wall-clock pacing.
"""

from __future__ import annotations

import asyncio
import json
import time
from contextlib import AbstractContextManager

import httpx
import pytest
import websockets
from websockets.exceptions import ConnectionClosed, InvalidStatus

from server.app import create_app
from server.embedded import bound_socket, serving

pytestmark = pytest.mark.timeout(120)


def live_server(settings) -> AbstractContextManager[str]:
    return serving(create_app(settings), settings, bound_socket())


async def recv(ws) -> dict:
    return json.loads(await asyncio.wait_for(ws.recv(), 20))


async def until(ws, kind: str) -> list[dict]:
    out = []
    while True:
        out.append(await recv(ws))
        if out[-1]["type"] == kind:
            return out


async def greet(ws) -> tuple[dict, dict]:
    welcome, state, presence = await recv(ws), await recv(ws), await recv(ws)
    assert (welcome["type"], state["type"], presence["type"]) == ("welcome", "state",
                                                                 "presence")
    return welcome, state


async def play(address: str) -> None:
    async with httpx.AsyncClient(base_url=f"http://{address}") as http:
        room_id = (await http.post("/api/rooms", json={"game": "eight_ball"})).json()["room_id"]
        tokens = [(await http.post(f"/api/rooms/{room_id}/join", json={"name": n})).json()
                  ["token"] for n in ("Ana", "Ben")]
    url = f"ws://{address}/ws/rooms/{room_id}"
    with pytest.raises(InvalidStatus) as refused:  # a foreign page is refused at handshake
        async with websockets.connect(f"{url}?token={tokens[0]}",
                                      origin="http://evil.example"):
            pass
    assert refused.value.response.status_code == 403

    a = await websockets.connect(f"{url}?token={tokens[0]}", origin=f"http://{address}")
    b = await websockets.connect(f"{url}?token={tokens[1]}")
    s = await websockets.connect(url)
    try:
        for ws in (a, b, s):
            await greet(ws)
        await until(a, "presence")
        await until(a, "presence")
        await until(b, "presence")

        # the break, streamed in real time; Ben drops mid-shot and comes back
        await a.send(json.dumps({"type": "shoot", "angle": 0.0, "speed": 9.0}))
        strike_seen = None
        while True:
            message = await recv(b)
            if message["type"] == "event" and message["kind"] == "strike":
                strike_seen = time.monotonic()
            if message["type"] == "frame" and message["tick"] >= 60:
                break
        await b.close()
        b = await websockets.connect(f"{url}?token={tokens[1]}")
        welcome, state = await greet(b)
        assert welcome["seat"] == 1
        assert state["phase"] == "rolling" and state["shot"]["tick"] >= 60
        resumed = await until(b, "state")
        frames = [m for m in resumed if m["type"] == "frame"]
        assert frames[0]["tick"] > state["shot"]["tick"]
        assert frames[-1]["tick"] == state["shot"]["ticks"] and frames[-1]["last"]
        assert resumed[-2]["type"] == "shot_result"
        watched = time.monotonic() - strike_seen
        assert watched >= 0.9 * state["shot"]["ticks"] / 120  # paced, not dumped

        spectator_view = await until(s, "state")
        player_view = await until(a, "state")
        assert spectator_view[-1]["match"] == player_view[-1]["match"] == resumed[-1]["match"]
        assert sum(m["type"] == "shot_result" for m in player_view) == 1

        # the next shot, by whoever's turn it is
        state = resumed[-1]
        turn = state["match"]["turn"]
        shooter = (a, b)[turn]
        if not any(row[0] == 0 for row in state["balls"]):  # scratched: ball in hand
            await shooter.send(json.dumps({"type": "place_cue", "x": 0.4, "y": 0.635}))
            await until(shooter, "state")
        await shooter.send(json.dumps({"type": "shoot", "angle": 2.0, "speed": 1.5}))
        second = await until(s, "state")
        result = [m for m in second if m["type"] == "shot_result"][0]
        assert result["shot"] == 2 and result["outcome"]["shooter"] == turn

        # a frame over 16 KiB: uvicorn closes with 1009
        await a.send(json.dumps({"type": "chat", "text": "x" * (20 * 1024)}))
        with pytest.raises(ConnectionClosed) as closed:
            while True:
                await recv(a)
        assert closed.value.rcvd is not None and closed.value.rcvd.code == 1009
    finally:
        for ws in (a, b, s):
            await ws.close()


def test_real_server_plays_shots_with_reconnection_mid_shot(settings):
    with live_server(settings.replace(pace=1.0)) as address:
        asyncio.run(play(address))


async def spectate_offering_deflate(address: str) -> tuple[str | None, dict]:
    """A spectator that offers permessage-deflate, as browsers do: the extensions the server
    accepted, and the `state` it then read."""
    async with httpx.AsyncClient(base_url=f"http://{address}") as http:
        room_id = (await http.post("/api/rooms", json={"game": "practice"})).json()["room_id"]
    async with websockets.connect(f"ws://{address}/ws/rooms/{room_id}",
                                  compression="deflate") as ws:
        _, state = await greet(ws)
        return ws.response.headers.get("Sec-WebSocket-Extensions"), state


@pytest.mark.parametrize("deflate", [False, True])
def test_permessage_deflate_is_accepted_only_when_enabled(settings, deflate):
    with live_server(settings.replace(ws_deflate=deflate)) as address:
        extensions, state = asyncio.run(spectate_offering_deflate(address))
    assert ("permessage-deflate" in (extensions or "")) is deflate
    assert state["room"]["game"] == "practice"
    assert state["table"]["length"] == pytest.approx(2.54)
