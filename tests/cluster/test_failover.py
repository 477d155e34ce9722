"""Three `python -m server` processes on one Redis and one database: a room opened through
one is listed and joined through another and played over WebSocket on its owner; the owner
is killed (kill -9) while a shot rolls; another process takes the room over from the store
within 15 s, the same tokens reconnect there, the shot is played again from its stored
start with the same result, the match goes on and its history has every shot once.

The game is the 9-ball rack of `games.NINE_BALL`: the break scratches, Ben puts the cue ball
down and strikes; the owner dies while that shot rolls. On the new owner it pockets a ball
on a foul and Ana, with ball in hand, plays the third shot."""

from __future__ import annotations

import asyncio

import httpx
import pytest
import websockets

from tests.support.games import (
    NINE_BALL,
    NINE_BALL_FOUL,
    NINE_BALL_FOUL_BALL,
    NINE_BALL_PLACE,
    shoot_message,
)

from .servers import Server, ServerSet
from .sockets import connect, place_cue, recv, send, until
from .takeover import all_closed, break_and_place, moved, seated

pytestmark = [pytest.mark.timeout(360), pytest.mark.redis, pytest.mark.postgres, pytest.mark.slow]
THIRD_SHOT = {"type": "shoot", "angle": 2.5, "speed": 2.0}
FAILOVER_WITHIN = 15.0  # s, from the kill to the room answering on another process


def test_a_room_survives_its_server_killed_mid_shot(servers) -> None:
    group: ServerSet = servers(3, rack_seed=NINE_BALL, pace=1.0)
    first, second, _ = group.all
    room, url, ana, ben = seated(first, second, race_to=2)
    with second.http() as two:
        listed = two.get("/api/rooms").json()
    assert [r["room_id"] for r in listed["rooms"]] == [room] and listed["total"] == 1
    owner = group.by_url(url)

    loop = asyncio.new_event_loop()
    try:
        seen = loop.run_until_complete(before_the_kill(url, ana, ben))
        with owner.http() as client:  # the second shot is rolling on its owner ...
            assert client.get(f"/api/rooms/{room}").json()["state"]["phase"] == "rolling"
        owner.kill()  # ... which dies now
        loop.run_until_complete(all_closed(seen["sockets"]))
        survivor = group.others(owner)[0]
        detail, took = moved(survivor, room, url, FAILOVER_WITHIN)
        assert took < FAILOVER_WITHIN
        new_url = detail["ws_url"]
        assert group.by_url(new_url) in group.others(owner)
        assert detail["players"] == ["Ana", "Ben"]
        loop.run_until_complete(after_the_kill(new_url, ana, ben, seen))
        history(survivor, room)
    finally:
        loop.close()


async def before_the_kill(url: str, ana: str, ben: str) -> dict:
    """The break (a scratch), Ben's cue ball placed, his shot struck and its stream
    begun."""
    a, b, placed = await break_and_place(url, ana, ben)
    await send(b, shoot_message(NINE_BALL_FOUL))
    while (await recv(b))["type"] in ("state", "presence", "aim"):
        pass  # up to the first message of the shot's motion
    return {"sockets": (a, b), "before": placed}


async def after_the_kill(url: str, ana: str, ben: str, ctx: dict) -> None:
    # a wrong token is refused on the new owner too; the stored hashes open the seats
    with pytest.raises(websockets.InvalidStatus):
        await websockets.connect(f"{url}?token=wrong")
    b, welcome, state = await connect(url, ben)
    assert welcome["seat"] == 1
    if state["phase"] == "rolling":  # the shot in flight, played again from its start
        assert state["match"] == ctx["before"]["match"]
        assert state["shot"]["id"] == 2 and state["shot"]["seat"] == 1
        resumed = await until(b, "state")
        result = next(m for m in resumed if m["type"] == "shot_result")
        outcome = result["outcome"]
        assert (result["shot"], outcome["shooter"]) == (2, 1)
        assert outcome["pocketed"] == [NINE_BALL_FOUL_BALL]
        assert [f["code"] for f in outcome["fouls"]] == ["wrong_ball_first"]
        state = resumed[-1]
    # the same result as the shot would have had: a foul that left the ball down
    assert state["phase"] == "aiming" and state["match"]["turn"] == 0
    assert state["match"]["ball_in_hand"] == "anywhere" and state["match"]["score"] == [0, 0]
    assert NINE_BALL_FOUL_BALL not in [row[0] for row in state["balls"]]

    # Ana comes back and the match goes on: ball in hand, the third shot
    a, welcome, again = await connect(url, ana)
    assert welcome["seat"] == 0 and again["match"] == state["match"]
    await place_cue(a, *NINE_BALL_PLACE)
    await send(a, THIRD_SHOT)
    third = await until(b, "shot_result")
    assert third[-1]["shot"] == 3 and third[-1]["outcome"]["shooter"] == 0
    for ws in (a, b):
        await ws.close()


def history(server: Server, room: str) -> None:
    """One match, every shot in it once, numbered in order (none lost to the kill, none
    doubled by playing it again)."""
    with server.http() as client:
        matches = client.get("/api/matches").json()["matches"]
        assert [m["room_id"] for m in matches] == [room]
        detail = client.get(f"/api/matches/{matches[0]['id']}").json()
    shots = detail["shots"]
    assert [s["shot_id"] for s in shots] == [s["n"] for s in shots] == [1, 2, 3]
    assert [s["seat"] for s in shots] == [0, 1, 0]


def test_two_joins_racing_through_two_servers_take_one_seat(servers) -> None:
    """A practice table has one seat: two processes forward their joins to its owner at the
    same moment; exactly one is seated, the other is told the table is full."""
    group: ServerSet = servers(3, store="sqlite", rack_seed=NINE_BALL)  # one shared file
    first, second, third = group.all
    with first.http() as client:
        rooms = [client.post("/api/rooms", json={"game": "practice"}).json() for _ in range(3)]

    async def race(room: str) -> list[httpx.Response]:
        async with (
            httpx.AsyncClient(base_url=second.url, timeout=20) as b,
            httpx.AsyncClient(base_url=third.url, timeout=20) as c,
        ):
            return list(
                await asyncio.gather(
                    b.post(f"/api/rooms/{room}/join", json={"name": "Bea"}),
                    c.post(f"/api/rooms/{room}/join", json={"name": "Cy"}),
                )
            )

    # three rooms: placed one on each process, so some race is through two non-owners
    assert len({group.by_url(r["ws_url"]).port for r in rooms}) == 3
    for room in rooms:
        replies = asyncio.run(race(room["room_id"]))
        assert sorted(r.status_code for r in replies) == [200, 409]
        seated = next(r.json() for r in replies if r.status_code == 200)
        full = next(r.json() for r in replies if r.status_code == 409)
        assert seated["seat"] == 0 and seated["ws_url"] == room["ws_url"]
        assert full["detail"]["code"] == "room_full"
