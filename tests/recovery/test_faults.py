"""Abuse and faults against a real uvicorn: many clients fuzzing the protocol at once, then
every room is still consistent and playable; a client killed in the middle of a shot."""

from __future__ import annotations

import asyncio
import json
import math
import random

import httpx
import numpy as np
import pytest
import websockets
from websockets.exceptions import ConnectionClosed

from server.engine import Table
from server.protocol.inbound import CLIENT_TYPES
from tests.support.games import BREAK_MESSAGE, EIGHT_BALL_BREAK_BALL
from tests.support.live import greet, http, live_server, recv, send, until, ws_url
from tests.support.messages import decoded
from tests.support.rooms import create_room, join, seated_room

pytestmark = pytest.mark.timeout(150)
TABLE = Table.pool("9ft")
LAST_PING = 10**6  # a fuzz client's last message: its pong says the server read them all
TYPES = sorted(CLIENT_TYPES)
ODD = [
    None,
    True,
    -1,
    0,
    7,
    1e308,
    -1e308,
    0.5,
    12.0001,
    "x",
    "",
    [],
    [1],
    {},
    {"a": 1},
    [0.0, 0.6],
    [0.5, 0.5],
    2**70,
    "\u0000",
    "🎱" * 300,
]


def fuzz_message(rng: random.Random) -> str | bytes:
    """Random and malformed messages, and now and then a well-formed one."""
    pick = rng.randrange(12)
    if pick == 0:
        return rng.randbytes(rng.randrange(1, 64))
    if pick == 1:
        return rng.choice(
            [
                "{",
                "}",
                "null",
                "[]",
                "42",
                '"shoot"',
                "{'type': 'shoot'}",
                '{"type": "shoot", "angle": NaN, "speed": 5}',
                '{"type": "shoot", "angle": Infinity, "speed": 5}',
                '{"type": "aim", "angle": 1, "power": -Infinity}',
                '{"type": ' * 50,
                "\ud800".encode("utf-8", "surrogatepass").decode("utf-8", "replace"),
            ]
        )
    if pick in (2, 3, 4):
        body = {"type": rng.choice([*TYPES, "warp", "", "SHOOT", None, 3])}
        for _ in range(rng.randrange(4)):
            body[
                rng.choice(
                    [
                        "angle",
                        "speed",
                        "tip",
                        "x",
                        "y",
                        "pocket",
                        "option",
                        "text",
                        "power",
                        "id",
                        "seat",
                        "extra",
                    ]
                )
            ] = rng.choice(ODD)
        return json.dumps(body)
    # well-formed, maybe out of turn, maybe illegal for the rules
    kind = rng.choice(TYPES)
    body: dict = {"type": kind}
    if kind == "shoot":
        body.update(
            angle=rng.uniform(-math.pi, math.pi),
            speed=rng.uniform(0.5, 9.0),
            tip=[rng.uniform(-0.3, 0.3), rng.uniform(-0.3, 0.3)],
        )
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


async def fuzz_client(address: str, room: str, token: str | None, seed: int, report: dict) -> None:
    rng = random.Random(seed)
    answered = asyncio.Event()
    async with websockets.connect(ws_url(address, room, token), max_size=2**22) as ws:

        async def read() -> None:
            try:
                async for raw in ws:
                    message = decoded(raw)  # JSON, or a shot's binary `motion`
                    if message["type"] == "error":
                        assert message["code"] and message["message"]
                        report["errors"] += 1
                    if message["type"] == "pong" and message["id"] == LAST_PING:
                        answered.set()
            finally:
                answered.set()  # closed: no pong is coming

        reader = asyncio.create_task(read())
        try:
            for _ in range(50):
                await ws.send(fuzz_message(rng))
                # real time between messages: the server's rate limit counts real seconds
                await asyncio.sleep(rng.uniform(0.03, 0.09))
            await send(ws, {"type": "ping", "id": LAST_PING})
            await asyncio.wait_for(answered.wait(), 20)
        except ConnectionClosed as exc:
            report["closed"].append(exc.rcvd.code if exc.rcvd else None)
        finally:
            reader.cancel()
            await asyncio.gather(reader, return_exceptions=True)


async def abuser(address: str, room: str, how: str) -> int | None:
    """A spectator that breaks a hard limit on purpose: the socket is closed with the right
    code. (Not a player: a fuzz client taking the same seat later would replace it.)"""
    ws = await websockets.connect(ws_url(address, room), max_size=2**22)
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


async def wait_at_rest(client: httpx.AsyncClient, room: str) -> dict:
    """Polls the room over HTTP (a bounded wait on a real server) until no shot rolls."""
    for _ in range(400):
        state = (await client.get(f"/api/rooms/{room}")).json()["state"]
        if state["phase"] != "rolling":
            return state
        await asyncio.sleep(0.05)
    raise AssertionError("the room never came to rest")


async def place_cue_anywhere_free(shooter) -> dict:
    """Ball in hand on a table the fuzzing left who knows how: try spots behind the head
    string until one is free; returns the shooter's `state`."""
    for x, y in ((0.5, 0.4), (0.3, 1.0), (0.45, 0.9), (0.2, 0.2), (0.55, 0.6), (0.1, 0.6)):
        await send(shooter, {"type": "place_cue", "x": x, "y": y})
        while (reply := await recv(shooter))["type"] not in ("state", "error"):
            pass
        if reply["type"] == "state":
            return reply
    raise AssertionError("no free spot for the cue ball")


async def play_one_shot(address: str, room: str, tokens: list[str]) -> None:
    """Reconnect the players and play: the room is still playable. Whatever the fuzzing
    left (its messages race each other, so no run ends the same): a finished match, a
    pending decision, ball in hand, a call to make."""
    sockets = [await websockets.connect(ws_url(address, room, t)) for t in tokens]
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
            await sockets[match["decision"]["seat"]].send(
                json.dumps({"type": "decide", "option": match["decision"]["options"][0]})
            )
            state = (await until(sockets[-1], "state"))[-1]
            match = state["match"]
        shooter = sockets[match["turn"]]
        if not any(r[0] == 0 for r in state["balls"]):
            await place_cue_anywhere_free(shooter)
        if match["requires_call"]:
            await shooter.send(json.dumps({"type": "call", "pocket": 2}))
            await until(shooter, "state")
        await shooter.send(json.dumps({"type": "shoot", "angle": 1.0, "speed": 2.0}))
        got = await until(sockets[-1], "shot_result")
        assert got[-1]["cause"] == "shot" and got[-1]["outcome"]["shooter"] == match["turn"]
    finally:
        for ws in sockets:
            await ws.close()


def open_rooms(address: str) -> list[tuple[str, str, list[str]]]:
    """An 8-ball, a 9-ball (both race to 3) and a practice room, seated: (kind, id, tokens)."""
    rooms = []
    with http(address) as client:
        for kind in ("eight_ball", "nine_ball"):
            room, ta, tb = seated_room(client, kind, race_to=3)
            rooms.append((kind, room, [ta, tb]))
        practice = create_room(client, "practice")
        rooms.append(("practice", practice, [join(client, practice, "Ana")["token"]]))
    return rooms


async def fuzz(address: str, rooms: list[tuple[str, str, list[str]]]) -> None:
    async with httpx.AsyncClient(base_url=f"http://{address}") as http_client:
        report: dict = {"errors": 0, "closed": []}
        clients = []
        for i, (_, room, tokens) in enumerate(rooms):
            for j, token in enumerate([*tokens, None, None]):
                clients.append(fuzz_client(address, room, token, 100 * i + j, report))
        abuse = [abuser(address, rooms[0][1], "flood"), abuser(address, rooms[1][1], "huge")]
        results = await asyncio.gather(*clients, *abuse)
        assert results[-2:] == [1008, 1009]
        assert report["errors"] > 100  # the junk was refused, message by message
        assert set(report["closed"]) <= {1008, 1009, 4000}

        assert (await http_client.get("/health")).json() == {"status": "ok"}
        for kind, room, tokens in rooms:
            state = await wait_at_rest(http_client, room)
            check_consistent(state, kind)
            await play_one_shot(address, room, tokens)
            check_consistent(await wait_at_rest(http_client, room), kind)


@pytest.mark.slow  # many seconds: not in scripts/test --quick
def test_many_clients_fuzzing_at_once_leave_every_room_consistent_and_playable(settings) -> None:
    with live_server(settings.replace(pace=20.0)) as address:
        asyncio.run(fuzz(address, open_rooms(address)))


async def kill_mid_shot(address: str, room: str, tokens: list[str]) -> None:
    """The break of `games.EIGHT_BALL` (a ball drops, Ana plays again); both players'
    connections die while it rolls."""
    a = await websockets.connect(ws_url(address, room, tokens[0]))
    b = await websockets.connect(ws_url(address, room, tokens[1]))
    s = await websockets.connect(ws_url(address, room))
    for ws in (a, b, s):
        await greet(ws)
    await send(a, BREAK_MESSAGE)
    while (await recv(b))["type"] != "motion":
        pass
    b.transport.abort()  # the process died: no close frame, the TCP connection just ends
    a.transport.abort()  # the shooter too
    seen = await until(s, "state")
    shown = [m["type"] for m in seen if m["type"] in ("motion", "shot_result", "state")]
    assert shown == ["motion", "shot_result", "state"]
    gone = [m for m in seen if m["type"] == "presence"]
    assert gone and not any(p["connected"] for p in gone[-1]["players"])
    assert seen[-2]["outcome"]["pocketed"] == [EIGHT_BALL_BREAK_BALL]
    after = seen[-1]
    assert after["match"]["turn"] == 0  # Ana's turn again, though she is away
    assert {g["seat"] for g in after["grace"]} == {0, 1}  # the seats wait for them
    b = await websockets.connect(ws_url(address, room, tokens[1]))
    welcome, state = await greet(b)
    assert welcome["seat"] == 1 and state["match"] == after["match"]
    assert state["phase"] == "aiming"
    for ws in (b, s):
        await ws.close()


def test_a_client_killed_mid_shot_does_not_disturb_the_room(settings) -> None:
    with live_server(settings.replace(pace=4.0)) as address, http(address) as client:
        room, ta, tb = seated_room(client)
        asyncio.run(kill_mid_shot(address, room, [ta, tb]))
