"""Restart recovery with a real uvicorn: stop the server in the middle of a shot, start a new
one on the same port and database, players reconnect with their tokens and play on; the
shot in flight is played again from its stored start, frame for frame the same."""

from __future__ import annotations

import asyncio
import json
from pathlib import Path

import httpx
import pytest
import websockets
from websockets.exceptions import ConnectionClosed

from .conftest import (
    free_port,
    greet,
    live_server,
    place_cue_ball,
    recv,
    shot_payload,
    until,
)

pytestmark = pytest.mark.timeout(150)


async def open_room(address: str) -> tuple[str, list[str]]:
    async with httpx.AsyncClient(base_url=f"http://{address}") as http:
        room = (await http.post("/api/rooms", json={"game": "nine_ball", "race_to": 2,
                                                    "shot_clock": 0})).json()["room_id"]
        tokens = [(await http.post(f"/api/rooms/{room}/join", json={"name": n})).json()
                  ["token"] for n in ("Ana", "Ben")]
    return room, tokens


async def connect(address: str, room: str, token: str | None):
    url = f"ws://{address}/ws/rooms/{room}" + (f"?token={token}" if token else "")
    ws = await websockets.connect(url)
    welcome, state = await greet(ws)
    return ws, welcome, state


async def before_restart(address: str) -> dict:
    """Play the break to the end, then strike a second shot and read a few of its frames."""
    room, tokens = await open_room(address)
    a, _, _ = await connect(address, room, tokens[0])
    b, _, _ = await connect(address, room, tokens[1])
    await a.send(json.dumps({"type": "shoot", "angle": 0.0, "speed": 9.0}))
    after_break = (await until(b, "state"))[-1]
    match = after_break["match"]
    shooter = (a, b)[match["turn"]]
    if match["decision"] is not None:  # none expected after a 9-ball break, but be sure
        await (a, b)[match["decision"]["seat"]].send(json.dumps(
            {"type": "decide", "option": match["decision"]["options"][0]}))
        after_break = (await until(b, "state"))[-1]
        shooter = (a, b)[after_break["match"]["turn"]]
    if not any(row[0] == 0 for row in after_break["balls"]):
        after_break = await place_cue_ball(shooter, b)
    await shooter.send(json.dumps({"type": "shoot", "angle": 0.4, "speed": 9.0}))
    seen = []
    while len([m for m in seen if m["type"] == "frame"]) < 4:
        seen.append(await recv(b))
    closes = []
    return {"room": room, "tokens": tokens, "sockets": (a, b), "before": after_break,
            "seen": seen, "closes": closes}


async def collect_close(ws) -> int | None:
    try:
        while True:
            await recv(ws, 20)
    except ConnectionClosed as exc:
        return exc.rcvd.code if exc.rcvd else None


def test_server_restart_mid_shot_loses_nothing(settings, db_path: Path) -> None:
    settings = settings.replace(pace=2.0)
    port = free_port()
    loop = asyncio.new_event_loop()
    try:
        with live_server(settings, db_path, port) as address:
            ctx = loop.run_until_complete(before_restart(address))
            closing = [loop.create_task(collect_close(ws)) for ws in ctx["sockets"]]
            loop.run_until_complete(asyncio.sleep(0))
        # the server is down: its sockets were closed with 1012 (restart, reconnect)
        assert loop.run_until_complete(asyncio.gather(*closing)) == [1012, 1012]

        with live_server(settings, db_path, port) as address:
            loop.run_until_complete(after_restart(address, ctx))
    finally:
        loop.close()


async def after_restart(address: str, ctx: dict) -> None:
    room, tokens = ctx["room"], ctx["tokens"]
    async with httpx.AsyncClient(base_url=f"http://{address}") as http:
        listed = (await http.get("/api/rooms")).json()["rooms"]
        assert [r["room_id"] for r in listed] == [room]
        assert listed[0]["players"] == ["Ana", "Ben"]
    # a wrong token is still refused; the stored hashes open the seats
    with pytest.raises(websockets.InvalidStatus):
        await websockets.connect(f"ws://{address}/ws/rooms/{room}?token=wrong")
    b, welcome, state = await connect(address, room, tokens[1])
    assert welcome["seat"] == 1
    # the shot in flight is being played again from its start
    assert state["phase"] == "rolling"
    before = ctx["before"]
    assert state["match"]["score"] == before["match"]["score"]
    assert state["match"]["turn"] == before["match"]["turn"]
    resumed = await until(b, "state")
    seen_before = [shot_payload(m) for m in ctx["seen"] if m["type"] == "frame"]
    seen_after = [shot_payload(m) for m in resumed if m["type"] == "frame"]
    assert seen_before and seen_after and seen_after[-1].get("last")
    result = next(m for m in resumed if m["type"] == "shot_result")
    assert result["shot"] == 2
    after = resumed[-1]
    assert after["phase"] in ("aiming", "over")

    # the other player comes back and the match goes on
    a, welcome, state = await connect(address, room, tokens[0])
    assert welcome["seat"] == 0 and state["match"] == after["match"]
    sockets = (a, b)
    match = after["match"]
    if after["phase"] == "aiming":
        if match["decision"] is not None:
            await sockets[match["decision"]["seat"]].send(json.dumps(
                {"type": "decide", "option": match["decision"]["options"][0]}))
            after = (await until(b, "state"))[-1]
            match = after["match"]
        shooter = sockets[match["turn"]]
        if not any(row[0] == 0 for row in after["balls"]):
            await place_cue_ball(shooter, b)
        await shooter.send(json.dumps({"type": "shoot", "angle": 2.5, "speed": 2.0}))
        third = await until(b, "state")
        assert [m["shot"] for m in third if m["type"] == "shot_result"] == [3]

    # every shot is in the history once, numbered in order
    async with httpx.AsyncClient(base_url=f"http://{address}") as http:
        matches = (await http.get("/api/matches")).json()["matches"]
        assert len(matches) == 1 and matches[0]["room_id"] == room
        detail = (await http.get(f"/api/matches/{matches[0]['id']}")).json()
    ids = [s["shot_id"] for s in detail["shots"]]
    assert ids == list(range(1, len(ids) + 1)) and len(ids) >= 2
    assert [s["n"] for s in detail["shots"]] == ids
    # the shot cut by the restart, before and after, is the stored shot frame for frame
    async with httpx.AsyncClient(base_url=f"http://{address}") as http:
        reply = await http.get(detail["shots"][1]["replay"], params={"pace": 100})
    full = {m["tick"]: shot_payload(m) for m in map(json.loads, reply.text.splitlines())
            if m["type"] == "frame"}
    assert all(full[m["tick"]] == m for m in seen_before + seen_after)
    for ws in sockets:
        await ws.close()
