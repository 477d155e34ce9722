"""Redis is only a meeting point: while it is down the rooms play on (players talk to their
room's owner directly); when it comes back empty, the owners take their leases and lobby
entries again, and a room whose owner died meanwhile, which only the store still knows, is
taken over from there with an epoch above the one the store has seen.

The game is the 9-ball rack of `games.NINE_BALL` (the break scratches)."""

from __future__ import annotations

import asyncio
import time

import pytest
from redis import Redis

from tests.support.games import NINE_BALL, NINE_BALL_BREAK, shoot_message
from tests.support.redis import RedisServer

from .servers import Server, ServerSet
from .sockets import connect, send, until

pytestmark = [pytest.mark.timeout(360), pytest.mark.redis, pytest.mark.postgres, pytest.mark.slow]


def listed(server: Server) -> list[str]:
    with server.http() as client:
        reply = client.get("/api/rooms")
    assert reply.status_code == 200, reply.text
    return sorted(r["room_id"] for r in reply.json()["rooms"])


def eventually(check, within: float = 20.0):
    deadline = time.monotonic() + within
    while True:
        try:
            return check()
        except AssertionError:
            if time.monotonic() > deadline:
                raise
            time.sleep(0.2)


def test_rooms_play_on_through_a_redis_restart(servers, redis: RedisServer) -> None:
    group: ServerSet = servers(2, rack_seed=NINE_BALL, lease_ttl=2.0)
    with group.all[0].http() as client:
        rooms = [
            client.post("/api/rooms", json={"game": "nine_ball", "shot_clock": 0}).json()
            for _ in range(2)
        ]
        kept = rooms[0]
        tokens = [
            client.post(f"/api/rooms/{kept['room_id']}/join", json={"name": n}).json()["token"]
            for n in ("Ana", "Ben")
        ]
    owner = group.by_url(kept["ws_url"])
    doomed = next(r for r in rooms if owner.address not in r["ws_url"])  # on the other one
    other = group.by_url(doomed["ws_url"])
    everything = sorted(r["room_id"] for r in rooms)
    assert listed(owner) == listed(other) == everything

    loop = asyncio.new_event_loop()
    try:
        a, _, _ = loop.run_until_complete(connect(kept["ws_url"], tokens[0]))
        b, _, _ = loop.run_until_complete(connect(kept["ws_url"], tokens[1]))
        redis.stop()
        # Redis is down: the room plays on, the lobby shows each server's own tables
        loop.run_until_complete(send(a, shoot_message(NINE_BALL_BREAK)))
        stream = loop.run_until_complete(until(b, "state"))
        result = next(m for m in stream if m["type"] == "shot_result")
        assert [f["code"] for f in result["outcome"]["fouls"]] == ["scratch"]
        assert listed(owner) == [kept["room_id"]]
        other.kill()  # and the other server dies while nobody can notice
        redis.start()  # back, empty

        # the owner announces its room again; the dead server's room is found in the
        # store and taken over by the survivor
        eventually(lambda: _assert_equal(listed(owner), everything))
        with owner.http() as client:
            detail = client.get(f"/api/rooms/{doomed['room_id']}").json()
        assert detail["ws_url"].startswith(f"ws://{owner.address}/")
        assert "1 rooms in the store had no owner" in owner.output()
        # the players never left: the match goes on, Ben has ball in hand
        loop.run_until_complete(send(b, {"type": "place_cue", "x": 0.5, "y": 0.4}))
        state = loop.run_until_complete(until(b, "state"))[-1]
        assert state["match"]["turn"] == 1 and state["phase"] == "aiming"
        for ws in (a, b):
            loop.run_until_complete(ws.close())
    finally:
        loop.close()


def _assert_equal(found: object, expected: object) -> None:
    assert found == expected


def test_a_room_redis_forgot_is_moving_not_unknown(servers, redis: RedisServer) -> None:
    """Redis came back empty and the room's owner has not renewed its lease yet (here it
    is paused): the room is in the store, so another process answers `503 room_moving`
    (the client asks again), never `404 unknown_room` (the client would give up)."""
    group: ServerSet = servers(2, rack_seed=NINE_BALL, lease_ttl=8.0, heartbeat=1.0)
    with group.all[0].http() as client:
        made = client.post("/api/rooms", json={"game": "nine_ball", "shot_clock": 0}).json()
        room = made["room_id"]
        assert client.post(f"/api/rooms/{room}/join", json={"name": "Ana"}).status_code == 200
    owner = group.by_url(made["ws_url"])
    other = group.others(owner)[0]
    owner.pause()
    try:
        redis.stop()
        redis.start()  # back, empty
        eventually(lambda: _assert_equal(_announced(redis), 1))  # the other one is back
        replies = []
        with other.http() as client:
            for _ in range(5):
                replies.append(client.get(f"/api/rooms/{room}"))
                time.sleep(0.2)
    finally:
        owner.resume()
    assert [r.status_code for r in replies] == [503] * 5, [r.text for r in replies]
    assert {r.json()["detail"]["code"] for r in replies} == {"room_moving"}
    with other.http() as client:  # and once an owner has it again, it is there
        eventually(lambda: _assert_equal(client.get(f"/api/rooms/{room}").status_code, 200))


def _announced(redis: RedisServer) -> int:
    with Redis.from_url(redis.url) as client:
        return int(client.scard("pool:nodes"))
