"""Redis is only a meeting point: while it is down the rooms play on (players talk to their
room's owner directly); when it comes back empty, the owners take their leases and lobby
entries again, and a room whose owner died meanwhile, which only the store still knows, is
taken over from there with an epoch above the one the store has seen.

The game is the 9-ball rack of `games.NINE_BALL` (the break scratches)."""

from __future__ import annotations

import asyncio
import time

import pytest

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


def _assert_equal(found: list[str], expected: list[str]) -> None:
    assert found == expected
