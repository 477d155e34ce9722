"""PostgreSQL out of reach under a live cluster (three real processes, PostgreSQL really
stopped and started): the owners keep their rooms, since liveness never waits on the store,
and a shot shown is a shot kept, since its motion waits until its start is stored.

The game is the 9-ball rack of `games.NINE_BALL`: the break scratches, Ben puts the cue ball
down and pockets a ball on a foul (`NINE_BALL_FOUL`), Ana with ball in hand plays a third
shot. What the players saw (each `shot_result`'s outcome) is compared with what the store
holds once PostgreSQL is back: every shot seen is there, with the outcome seen (none undone,
none rewritten)."""

from __future__ import annotations

import asyncio
import contextlib
import threading
import time
from typing import Any

import httpx
import pytest
from redis import Redis

from tests.support.games import NINE_BALL, NINE_BALL_FOUL, NINE_BALL_PLACE, shoot_message
from tests.support.postgres import PostgresServer
from tests.support.redis import RedisServer

from .servers import Server, ServerSet
from .sockets import connect, place_cue, recv, send, until
from .takeover import all_closed, break_and_place, moved, seated

pytestmark = [pytest.mark.timeout(420), pytest.mark.redis, pytest.mark.postgres, pytest.mark.slow]
THIRD_SHOT = {"type": "shoot", "angle": 2.5, "speed": 2.0}
OUTAGE = 15.0  # s: past the lease (3 s here) and a read's deadline (10 s)


def test_an_outage_with_lobby_traffic_moves_no_room_and_loses_no_shot(
    servers, postgres: PostgresServer, redis: RedisServer
) -> None:
    group: ServerSet = servers(3, rack_seed=NINE_BALL)
    room, url, ana, ben = seated(group.all[0], group.all[1], race_to=2)
    owner = group.by_url(url)
    lease_before = lease_of(redis, room)
    loop = asyncio.new_event_loop()
    try:
        a, b, _ = loop.run_until_complete(break_and_place(url, ana, ben))
        seen = {1: None}  # the break: seen, checked against the store below
        postgres.stop()
        try:
            with LobbyTraffic(group.all) as lobby:
                # Ben strikes: the table waits for the shot's start to be stored, and says so
                notice = loop.run_until_complete(strike_unstored(b, shoot_message(NINE_BALL_FOUL)))
                assert notice["code"] == "saving"
                announced = []  # every process stays announced: liveness waits on no store
                for _ in range(int(2 * (OUTAGE - 2.0))):
                    announced.append(presences(redis))
                    loop.run_until_complete(asyncio.sleep(0.5))  # sockets kept alive
        finally:
            postgres.start()
        assert set(announced) == {3}, announced
        assert lobby.codes and lobby.codes <= {201, 503}, lobby.codes  # refused, never a 500
        second = result_of(loop.run_until_complete(until(b, "shot_result", timeout=60)))
        seen[2] = second["outcome"]
        assert second["outcome"]["pocketed"] == [6]
        # the same sockets, the same owner: the match goes on
        loop.run_until_complete(shown_to_the_end(a, 2))
        loop.run_until_complete(place_cue(a, *NINE_BALL_PLACE))
        loop.run_until_complete(send(a, THIRD_SHOT))
        seen[3] = result_of(loop.run_until_complete(until(b, "shot_result")))["outcome"]
        for ws in (a, b):
            loop.run_until_complete(ws.close())
    finally:
        loop.close()
    assert lease_of(redis, room) == lease_before  # never moved, never re-leased
    for server in group.all:
        for moving in ("owned elsewhere now", "took over", "leases were gone"):
            assert moving not in server.output()
    assert stored_outcomes(owner, room, seen) == {n: o for n, o in seen.items() if o}


def test_an_outage_and_the_owner_killed_undo_no_shot_seen(
    servers, postgres: PostgresServer
) -> None:
    group: ServerSet = servers(3, rack_seed=NINE_BALL, pace=1.0)
    room, url, ana, ben = seated(group.all[0], group.all[1], race_to=2)
    owner = group.by_url(url)
    loop = asyncio.new_event_loop()
    try:
        a, b, _ = loop.run_until_complete(break_and_place(url, ana, ben))
        # Ben's shot starts (its start stored: the motion comes) and PostgreSQL goes down
        # while it rolls: its record and the room after it are only queued
        loop.run_until_complete(send(b, shoot_message(NINE_BALL_FOUL)))
        loop.run_until_complete(until(b, "motion"))
        postgres.stop("immediate")
        try:
            shown = loop.run_until_complete(until(b, "state"))
            second = result_of(shown)
            assert second["outcome"]["pocketed"] == [6]
            table_after_second = shown[-1]["balls"]
            # Ana places the cue ball and strikes: nothing can store it, nothing is shown
            seen_by_ana = loop.run_until_complete(shown_to_the_end(a, 2))
            assert seen_by_ana[-1]["balls"] == table_after_second
            loop.run_until_complete(place_cue(a, *NINE_BALL_PLACE))
            notice = loop.run_until_complete(strike_unstored(a, THIRD_SHOT))
            assert notice["code"] == "saving"
            owner.kill()  # and the owner dies with its queued writes
            loop.run_until_complete(all_closed((a, b)))
            loop.run_until_complete(asyncio.sleep(5.0))  # its lease lapses meanwhile
        finally:
            postgres.start()
        survivor = group.others(owner)[0]
        detail, _ = moved(survivor, room, url, within=60.0)
        replayed = loop.run_until_complete(
            after_the_move(detail["ws_url"], ana, ben, second["outcome"], table_after_second)
        )
    finally:
        loop.close()
    seen = {1: None, 2: second["outcome"], 3: replayed}
    assert stored_outcomes(survivor, room, seen) == {2: seen[2], 3: seen[3]}


async def after_the_move(
    url: str, ana: str, ben: str, second: dict[str, Any], table: list[Any]
) -> dict[str, Any]:
    """On the new owner: Ben's shot (seen to its end) is replayed from its stored start to
    the same outcome and table, never undone; Ana's (never shown) is hers to play again.
    Returns the outcome of Ana's shot as played there."""
    b, _, state = await connect(url, ben)
    if state["phase"] == "rolling":  # the shot seen, played again from its stored start
        replay = await until(b, "state")
        assert result_of(replay)["outcome"] == second
        state = replay[-1]
    assert state["balls"] == table  # the table the players saw after it
    assert state["phase"] == "aiming" and state["match"]["turn"] == 0
    assert state["match"]["ball_in_hand"] == "anywhere"
    a, _, _ = await connect(url, ana)
    await place_cue(a, *NINE_BALL_PLACE)
    await send(a, THIRD_SHOT)
    third = result_of(await until(b, "shot_result"))
    assert third["shot"] == 3
    for ws in (a, b):
        await ws.close()
    return third["outcome"]


async def strike_unstored(ws: Any, shoot: dict[str, Any]) -> dict[str, Any]:
    """Strike with the store out of reach: the first answer that is not the table's own
    chatter is the notice that the table is being saved (no motion before it)."""
    await send(ws, shoot)
    while (message := await recv(ws, 20))["type"] in ("state", "presence", "aim"):
        pass
    assert message["type"] == "error", message  # not "motion": nothing shown unstored
    return message


async def shown_to_the_end(ws: Any, shot: int) -> list[dict[str, Any]]:
    """Read a member's socket up to the `state` after shot `shot`'s result."""
    messages = await until(ws, "shot_result")
    while messages[-1]["shot"] != shot:
        messages += await until(ws, "shot_result")
    return messages + await until(ws, "state")


def result_of(messages: list[dict[str, Any]]) -> dict[str, Any]:
    return next(m for m in messages if m["type"] == "shot_result")


def lease_of(redis: RedisServer, room: str) -> str | None:
    with Redis.from_url(redis.url, decode_responses=True) as client:
        return client.get(f"pool:lease:{room}")


def presences(redis: RedisServer) -> int:
    """How many processes are announced in Redis now (their presence key alive)."""
    with Redis.from_url(redis.url, decode_responses=True) as client:
        nodes = client.smembers("pool:nodes")
        return sum(bool(client.exists(f"pool:node:{node}")) for node in nodes)


def stored_outcomes(server: Server, room: str, seen: dict[int, Any]) -> dict[int, dict[str, Any]]:
    """The store's outcome of each shot the players saw (None: seen, any outcome), once
    every shot is there; each shot id once."""
    with server.http() as client:
        deadline = time.monotonic() + 30
        while True:
            matches = client.get("/api/matches").json()["matches"]
            assert [m["room_id"] for m in matches] == [room]
            shots = client.get(f"/api/matches/{matches[0]['id']}").json()["shots"]
            if len(shots) >= len(seen) or time.monotonic() > deadline:
                break
            time.sleep(0.2)
    assert [s["shot_id"] for s in shots] == sorted(seen)
    return {s["shot_id"]: s["outcome"] for s in shots if seen[s["shot_id"]] is not None}


class LobbyTraffic:
    """Tables opened through every process, one request after another on each, until the
    block ends: what a lobby does while PostgreSQL is down (each waits for its answer)."""

    def __init__(self, servers: list[Server]) -> None:
        self.servers = servers
        self.codes: set[int] = set()
        self._stop = threading.Event()
        self._threads = [threading.Thread(target=self._open, args=(s,)) for s in servers]

    def __enter__(self) -> LobbyTraffic:
        for thread in self._threads:
            thread.start()
        return self

    def __exit__(self, *_: object) -> None:
        self._stop.set()
        for thread in self._threads:
            thread.join(30)

    def _open(self, server: Server) -> None:
        with httpx.Client(base_url=server.url, timeout=30) as client:
            while not self._stop.is_set():
                with contextlib.suppress(httpx.TransportError):
                    reply = client.post("/api/rooms", json={"game": "nine_ball"})
                    self.codes.add(reply.status_code)
