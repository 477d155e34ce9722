"""Restart recovery with a real uvicorn: stop the server in the middle of a shot, start a new
one on the same port and database, players reconnect with their tokens and play on; the
shot in flight is played again from its stored start, frame for frame the same.

The game is the 9-ball rack of `games.NINE_BALL`: the break scratches, Ben puts the cue ball
down and strikes; the server stops while that shot rolls. After the restart it pockets a
ball on a foul and Ana, with ball in hand, plays the third shot."""

from __future__ import annotations

import asyncio
import base64
import json

import httpx
import pytest
import websockets
from websockets.exceptions import ConnectionClosed

from server.protocol.motion import decode_motion
from tests.support.games import (
    NINE_BALL,
    NINE_BALL_BREAK,
    NINE_BALL_FOUL,
    NINE_BALL_FOUL_BALL,
    NINE_BALL_PLACE,
    shoot_message,
)
from tests.support.live import (
    greet,
    http,
    live_server,
    place_cue,
    recv,
    send,
    until,
    ws_url,
)
from tests.support.messages import shot_payload
from tests.support.ports import free_port
from tests.support.rooms import seated_room

pytestmark = pytest.mark.timeout(150)
THIRD_SHOT = {"type": "shoot", "angle": 2.5, "speed": 2.0}


async def connect(address: str, room: str, token: str | None):
    ws = await websockets.connect(ws_url(address, room, token))
    welcome, state = await greet(ws)
    return ws, welcome, state


async def before_restart(address: str, room: str, tokens: list[str]) -> dict:
    """The break (a scratch), Ben's cue ball placed, his shot struck and shown a while."""
    a, _, _ = await connect(address, room, tokens[0])
    b, _, _ = await connect(address, room, tokens[1])
    await send(a, shoot_message(NINE_BALL_BREAK))
    stream = await until(b, "state")
    result, after_break = stream[-2], stream[-1]
    assert result["outcome"]["pocketed"] == [0]
    assert [f["code"] for f in result["outcome"]["fouls"]] == ["scratch"]
    assert after_break["match"]["turn"] == 1
    assert after_break["match"]["ball_in_hand"] == "anywhere"
    placed = await place_cue(b, *NINE_BALL_PLACE)
    assert placed["balls"][0][:3] == [0, 500, 400]
    await send(b, shoot_message(NINE_BALL_FOUL))
    seen = [await recv(b)]
    while seen[-1]["type"] != "motion":
        seen.append(await recv(b))
    await asyncio.sleep(0.1)  # the shot is being shown
    return {"room": room, "tokens": tokens, "sockets": (a, b), "before": placed, "seen": seen}


async def close_all(sockets) -> None:
    for ws in sockets:
        await ws.close()


async def collect_close(ws) -> int | None:
    try:
        while True:
            await recv(ws, 20)
    except ConnectionClosed as exc:
        return exc.rcvd.code if exc.rcvd else None


@pytest.mark.slow  # many seconds: not in scripts/test --quick
def test_server_restart_mid_shot_loses_nothing(settings) -> None:
    settings = settings.replace(pace=2.0)
    port = free_port()
    loop = asyncio.new_event_loop()
    try:
        with live_server(settings, NINE_BALL, port) as address, http(address) as client:
            room, ta, tb = seated_room(client, "nine_ball", race_to=2, shot_clock=0)
            ctx = loop.run_until_complete(before_restart(address, room, [ta, tb]))
            closing = [loop.create_task(collect_close(ws)) for ws in ctx["sockets"]]
            loop.run_until_complete(asyncio.sleep(0))  # let them start reading
        # the server is down: its sockets were closed with 1012 (restart, reconnect)
        assert loop.run_until_complete(asyncio.gather(*closing)) == [1012, 1012]
        loop.run_until_complete(close_all(ctx["sockets"]))

        with live_server(settings, NINE_BALL, port) as address:
            loop.run_until_complete(after_restart(address, ctx))
    finally:
        loop.close()


async def after_restart(address: str, ctx: dict) -> None:
    room, tokens = ctx["room"], ctx["tokens"]
    async with httpx.AsyncClient(base_url=f"http://{address}") as client:
        listed = (await client.get("/api/rooms")).json()["rooms"]
        assert [r["room_id"] for r in listed] == [room]
        assert listed[0]["players"] == ["Ana", "Ben"]
    # a wrong token is still refused; the stored hashes open the seats
    with pytest.raises(websockets.InvalidStatus):
        await websockets.connect(ws_url(address, room, "wrong"))
    b, welcome, state = await connect(address, room, tokens[1])
    assert welcome["seat"] == 1
    # the shot in flight is being played again from its start
    assert state["phase"] == "rolling"
    before = ctx["before"]
    assert state["match"] == before["match"]  # the match as it was at the strike
    assert state["shot"]["id"] == 2 and state["shot"]["seat"] == 1
    resumed = await until(b, "state")
    (seen_before,) = [shot_payload(m) for m in ctx["seen"] if m["type"] == "motion"]
    (seen_after,) = [shot_payload(m) for m in resumed if m["type"] == "motion"]
    assert seen_after == seen_before  # played again from its start: the same motion
    result = next(m for m in resumed if m["type"] == "shot_result")
    assert result["shot"] == 2
    outcome = result["outcome"]
    assert (outcome["shooter"], outcome["pocketed"]) == (1, [NINE_BALL_FOUL_BALL])
    assert outcome["spotted"] == []
    assert [f["code"] for f in outcome["fouls"]] == ["wrong_ball_first"]
    after = resumed[-1]
    assert after["phase"] == "aiming" and after["match"]["turn"] == 0
    assert after["match"]["ball_in_hand"] == "anywhere" and after["match"]["score"] == [0, 0]
    assert NINE_BALL_FOUL_BALL not in [row[0] for row in after["balls"]]  # stays down

    # the other player comes back and the match goes on: Ana has ball in hand
    a, welcome, state = await connect(address, room, tokens[0])
    assert welcome["seat"] == 0 and state["match"] == after["match"]
    await place_cue(a, *NINE_BALL_PLACE)
    await send(a, THIRD_SHOT)
    third = await until(b, "shot_result")
    assert third[-1]["shot"] == 3 and third[-1]["outcome"]["shooter"] == 0

    # every shot is in the history once, numbered in order
    async with httpx.AsyncClient(base_url=f"http://{address}") as client:
        matches = (await client.get("/api/matches")).json()["matches"]
        assert len(matches) == 1 and matches[0]["room_id"] == room
        detail = (await client.get(f"/api/matches/{matches[0]['id']}")).json()
    assert [s["shot_id"] for s in detail["shots"]] == [s["n"] for s in detail["shots"]] == [1, 2, 3]
    # the shot cut by the restart, before and after, is the stored shot, knot for knot
    async with httpx.AsyncClient(base_url=f"http://{address}") as client:
        reply = await client.get(detail["shots"][1]["replay"], params={"pace": 100})
    (line,) = [m for m in map(json.loads, reply.text.splitlines()) if m["type"] == "motion"]
    assert shot_payload(decode_motion(base64.b64decode(line["data"]))) == seen_before
    for ws in (a, b):
        await ws.close()
