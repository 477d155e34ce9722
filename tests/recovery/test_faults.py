"""Abuse and faults against a real uvicorn: many clients fuzzing the protocol at once, then
every room is still consistent and playable; a client killed in the middle of a shot."""

from __future__ import annotations

import asyncio
import json
import math
import random
from pathlib import Path

import httpx
import numpy as np
import pytest
import websockets
from websockets.exceptions import ConnectionClosed

from server.engine import Table

from .conftest import free_port, greet, live_server, place_cue_ball, recv, until

pytestmark = pytest.mark.timeout(150)
TABLE = Table.pool("9ft")
TYPES = ["shoot", "place_cue", "aim", "call", "decide", "push_out", "rerack", "chat",
         "rematch", "concede", "sync", "ping"]
ODD = [None, True, -1, 0, 7, 1e308, -1e308, 0.5, 12.0001, "x", "", [], [1], {}, {"a": 1},
       [0.0, 0.6], [0.5, 0.5], 2**70, "\u0000", "🎱" * 300]


def fuzz_message(rng: random.Random) -> str | bytes:
    """Random and malformed messages, and now and then a well-formed one."""
    pick = rng.randrange(12)
    if pick == 0:
        return rng.randbytes(rng.randrange(1, 64))
    if pick == 1:
        return rng.choice(["{", "}", "null", "[]", "42", '"shoot"', "{'type': 'shoot'}",
                           '{"type": "shoot", "angle": NaN, "speed": 5}',
                           '{"type": "shoot", "angle": Infinity, "speed": 5}',
                           '{"type": "aim", "angle": 1, "power": -Infinity}',
                           '{"type": ' * 50, "\ud800".encode("utf-8", "surrogatepass")
                           .decode("utf-8", "replace")])
    if pick in (2, 3, 4):
        body = {"type": rng.choice(TYPES + ["warp", "", "SHOOT", None, 3])}
        for _ in range(rng.randrange(4)):
            body[rng.choice(["angle", "speed", "tip", "x", "y", "pocket", "option", "text",
                             "power", "id", "seat", "extra"])] = rng.choice(ODD)
        return json.dumps(body)
    # well-formed, maybe out of turn, maybe illegal for the rules
    kind = rng.choice(TYPES)
    body: dict = {"type": kind}
    if kind == "shoot":
        body.update(angle=rng.uniform(-math.pi, math.pi), speed=rng.uniform(0.5, 9.0),
                    tip=[rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3)])
    elif kind == "place_cue":
        body.update(x=rng.uniform(-0.5, 3.0), y=rng.uniform(-0.5, 1.8))
    elif kind == "aim":
        body.update(angle=rng.uniform(-3, 3), power=rng.random())
    elif kind == "call":
        body.update(pocket=rng.randrange(6))
    elif kind == "decide":
        body.update(option=rng.choice(["accept", "rerack", "shoot", "pass", "nope"]))
    elif kind == "chat":
        body.update(text="gl hf " * rng.randrange(1, 10))
    elif kind == "ping":
        body.update(id=rng.randrange(1000))
    elif kind == "concede" and rng.random() < 0.7:
        body = {"type": "sync"}  # concessions end games quickly: keep them rare
    return json.dumps(body)


async def fuzz_client(address: str, room: str, token: str | None, seed: int,
                      report: dict) -> None:
    rng = random.Random(seed)
    url = f"ws://{address}/ws/rooms/{room}" + (f"?token={token}" if token else "")
    async with websockets.connect(url, max_size=2**22) as ws:
        async def read() -> None:
            async for raw in ws:
                message = json.loads(raw)
                if message["type"] == "error":
                    assert message["code"] and message["message"]
                    report["errors"] += 1
        reader = asyncio.create_task(read())
        try:
            for _ in range(50):
                await ws.send(fuzz_message(rng))
                await asyncio.sleep(rng.uniform(0.03, 0.09))  # under the rate limit
            await ws.send(json.dumps({"type": "ping", "id": 1}))
            await asyncio.sleep(0.2)
        except ConnectionClosed as exc:
            report["closed"].append(exc.rcvd.code if exc.rcvd else None)
        finally:
            reader.cancel()
            await asyncio.gather(reader, return_exceptions=True)


async def abuser(address: str, room: str, token: str, how: str) -> int | None:
    """Breaks a hard limit on purpose: the socket is closed with the right code."""
    ws = await websockets.connect(f"ws://{address}/ws/rooms/{room}?token={token}",
                                  max_size=2**22)
    try:
        if how == "flood":
            for i in range(200):
                await ws.send(json.dumps({"type": "ping", "id": i}))
        else:
            await ws.send(json.dumps({"type": "chat", "text": "x" * 20000}))
        while True:
            await recv(ws, 10)
    except ConnectionClosed as exc:
        return exc.rcvd.code if exc.rcvd else None
    finally:
        await ws.close()


def check_consistent(state: dict, kind: str) -> None:
    assert state["phase"] in ("aiming", "over")
    match = state["match"]
    assert match is not None and match["kind"] == kind
    rows = state["balls"]
    ids = [r[0] for r in rows]
    assert len(ids) == len(set(ids))
    on = {b["id"]: (b["x"], b["y"]) for b in match["balls"] if b["on_table"]}
    assert set(on) == set(ids)
    pos = np.array(list(on.values()))
    assert all(TABLE.contains(x, y, margin=-1e-9) for x, y in pos)
    d = np.linalg.norm(pos[:, None] - pos[None, :], axis=2)
    d[np.diag_indices(len(pos))] = np.inf
    assert d.min() >= 2 * TABLE.ball_radius - 1e-9
    seats = 1 if kind == "practice" else 2
    assert match["turn"] in range(seats)
    assert len(match["score"]) == seats and all(s >= 0 for s in match["score"])
    assert sum(match["score"]) == match["games_played"] or match["match_over"]


async def wait_at_rest(http: httpx.AsyncClient, room: str) -> dict:
    for _ in range(400):
        state = (await http.get(f"/api/rooms/{room}")).json()["state"]
        if state["phase"] != "rolling":
            return state
        await asyncio.sleep(0.05)
    raise AssertionError("the room never came to rest")


async def play_one_shot(address: str, room: str, tokens: list[str]) -> None:
    """Reconnect the players and play: the room is still playable."""
    url = f"ws://{address}/ws/rooms/{room}"
    sockets = [await websockets.connect(f"{url}?token={t}") for t in tokens]
    try:
        state = (await greet(sockets[-1]))[1]
        if state["phase"] == "over":
            for ws in sockets:
                await ws.send(json.dumps({"type": "rematch"}))
            state = (await until(sockets[-1], "state"))[-1]
            while state["phase"] != "aiming":
                state = (await until(sockets[-1], "state"))[-1]
        match = state["match"]
        if match["decision"] is not None:
            await sockets[match["decision"]["seat"]].send(json.dumps(
                {"type": "decide", "option": match["decision"]["options"][0]}))
            state = (await until(sockets[-1], "state"))[-1]
            match = state["match"]
        shooter = sockets[match["turn"]]
        if not any(r[0] == 0 for r in state["balls"]):
            await place_cue_ball(shooter, shooter)
        if match["requires_call"]:
            await shooter.send(json.dumps({"type": "call", "pocket": 2}))
            await until(shooter, "state")
        await shooter.send(json.dumps({"type": "shoot", "angle": 1.0, "speed": 2.0}))
        got = await until(sockets[-1], "shot_result")
        assert got[-1]["cause"] == "shot" and got[-1]["outcome"]["shooter"] == match["turn"]
    finally:
        for ws in sockets:
            await ws.close()


async def fuzz(address: str) -> None:
    rooms = []
    async with httpx.AsyncClient(base_url=f"http://{address}") as http:
        for kind in ("eight_ball", "nine_ball", "practice"):
            room = (await http.post("/api/rooms", json={"game": kind, "race_to": 3})).json()
            names = ["Ana"] if kind == "practice" else ["Ana", "Ben"]
            tokens = [(await http.post(f"/api/rooms/{room['room_id']}/join",
                                       json={"name": n})).json()["token"] for n in names]
            rooms.append((kind, room["room_id"], tokens))
        report: dict = {"errors": 0, "closed": []}
        clients = []
        for i, (_, room, tokens) in enumerate(rooms):
            for j, token in enumerate([*tokens, None, None]):
                clients.append(fuzz_client(address, room, token, 100 * i + j, report))
        abuse = [abuser(address, rooms[0][1], rooms[0][2][0], "flood"),
                 abuser(address, rooms[1][1], rooms[1][2][1], "huge")]
        results = await asyncio.gather(*clients, *abuse)
        assert results[-2:] == [1008, 1009]
        assert report["errors"] > 100  # the junk was refused, message by message
        assert set(report["closed"]) <= {1008, 1009, 4000}

        assert (await http.get("/health")).json() == {"status": "ok"}
        for kind, room, tokens in rooms:
            state = await wait_at_rest(http, room)
            check_consistent(state, kind)
            await play_one_shot(address, room, tokens)
            check_consistent(await wait_at_rest(http, room), kind)


def test_many_clients_fuzzing_at_once_leave_every_room_consistent_and_playable(
        settings, db_path: Path) -> None:
    with live_server(settings.replace(pace=20.0), db_path, free_port()) as address:
        asyncio.run(fuzz(address))


async def kill_mid_shot(address: str) -> None:
    async with httpx.AsyncClient(base_url=f"http://{address}") as http:
        room = (await http.post("/api/rooms", json={"game": "eight_ball"})).json()["room_id"]
        tokens = [(await http.post(f"/api/rooms/{room}/join", json={"name": n})).json()
                  ["token"] for n in ("Ana", "Ben")]
    url = f"ws://{address}/ws/rooms/{room}"
    a = await websockets.connect(f"{url}?token={tokens[0]}")
    b = await websockets.connect(f"{url}?token={tokens[1]}")
    s = await websockets.connect(url)
    for ws in (a, b, s):
        await greet(ws)
    await a.send(json.dumps({"type": "shoot", "angle": 0.0, "speed": 9.0}))
    while (await recv(b))["type"] != "frame":
        pass
    b.transport.abort()  # the process died: no close frame, the TCP connection just ends
    a.transport.abort()  # the shooter too
    seen = await until(s, "state")
    frames = [m for m in seen if m["type"] == "frame"]
    assert frames[-1].get("last") and [m["type"] for m in seen[-2:]] == ["shot_result",
                                                                         "state"]
    ticks = [m["tick"] for m in frames]
    assert ticks == sorted(ticks)
    gone = [m for m in seen if m["type"] == "presence"]
    assert gone and not any(p["connected"] for p in gone[-1]["players"])
    after = seen[-1]
    assert {g["seat"] for g in after["grace"]} == {0, 1}  # the seats wait for them
    b = await websockets.connect(f"{url}?token={tokens[1]}")
    welcome, state = await greet(b)
    assert welcome["seat"] == 1 and state["match"] == after["match"]
    assert state["phase"] == "aiming"
    for ws in (b, s):
        await ws.close()


def test_a_client_killed_mid_shot_does_not_disturb_the_room(settings, db_path: Path) -> None:
    with live_server(settings.replace(pace=4.0), db_path, free_port()) as address:
        asyncio.run(kill_mid_shot(address))
