"""Play now across real `python -m server` processes sharing a private Redis and
PostgreSQL: 100 players, each pressing Play now on one of three processes at once, land in
50 rooms, nobody twice; leaving and the computer's offer work through any process; a
ranked room taken over after its server was killed is still rated."""

from __future__ import annotations

import asyncio
import time
from collections.abc import Iterator
from pathlib import Path

import httpx
import pytest

from server.store import Database
from server.store.players import PlayerRows
from tests.cluster.servers import ServerSet
from tests.support import waiting
from tests.support.games import EIGHT_BALL
from tests.support.postgres import PostgresServer, postgres  # noqa: F401  (a fixture)
from tests.support.redis import RedisServer, redis  # noqa: F401  (a fixture)
from tests.support.visits import visit_and_concede

pytestmark = [pytest.mark.timeout(180), pytest.mark.redis, pytest.mark.postgres, pytest.mark.slow]
COOKIE = "pool_player"


@pytest.fixture
def cluster(
    redis: RedisServer,  # noqa: F811
    postgres: PostgresServer,  # noqa: F811
    tmp_path: Path,
) -> Iterator[ServerSet]:
    settings = {"database_url": postgres.create_database(), "player_create_rate": "1000/minute"}
    group = ServerSet.start(3, redis.url, tmp_path, settings)
    try:
        yield group
    finally:
        for server in group.all:
            server.stop()


async def _press(bases: list[str], count: int) -> list[dict]:
    async def profile(base: str) -> str:
        async with httpx.AsyncClient(base_url=base, timeout=30) as setup:
            return (await setup.get("/api/players/me")).cookies[COOKIE]

    homes = [bases[i % len(bases)] for i in range(count)]
    secrets = [await profile(base) for base in homes]

    async def one(base: str, secret: str) -> dict:
        headers = {"Cookie": f"{COOKIE}={secret}"}
        async with httpx.AsyncClient(base_url=base, timeout=30, headers=headers) as browser:
            pressed = (await browser.post("/api/playnow", json={"game": "nine_ball"})).json()
            while pressed["status"] == "waiting":
                pressed = (await browser.get("/api/playnow", params={"wait": 10})).json()
            me = (await browser.get("/api/players/me")).json()
            return {"id": me["id"], "name": me["name"], **pressed}

    return await asyncio.gather(*(one(b, s) for b, s in zip(homes, secrets, strict=True)))


def test_a_hundred_presses_over_three_processes_make_fifty_rooms(cluster: ServerSet):
    bases = [server.url for server in cluster.all]
    seen = asyncio.run(_press(bases, 100))
    assert all(s["status"] == "matched" for s in seen), [s["status"] for s in seen]
    rooms: dict[str, list[dict]] = {}
    for s in seen:
        rooms.setdefault(s["room"]["room_id"], []).append(s)
    assert len(rooms) == 50
    assert len({s["id"] for s in seen}) == 100  # nobody twice
    with httpx.Client(base_url=bases[0], timeout=20) as http:
        for room_id, pair in rooms.items():
            assert sorted(p["room"]["seat"] for p in pair) == [0, 1]
            shown = http.get(f"/api/rooms/{room_id}").json()  # any process finds it
            by_seat = sorted(pair, key=lambda p: p["room"]["seat"])
            assert shown["players"] == [p["name"] for p in by_seat]
            assert shown["status"] == "playing"


def browser(base: str) -> httpx.Client:
    """A client with a fresh profile on the server at `base`."""
    made = httpx.get(f"{base}/api/players/me", timeout=20)
    secret = made.cookies[COOKIE]
    return httpx.Client(base_url=base, timeout=20, headers={"Cookie": f"{COOKIE}={secret}"})


def test_leaving_and_the_computer_offer_work_on_any_process(
    redis: RedisServer,  # noqa: F811
    postgres: PostgresServer,  # noqa: F811
    tmp_path: Path,
):
    settings = {"database_url": postgres.create_database(), "playnow_computer_after": 1.0}
    group = ServerSet.start(2, redis.url, tmp_path, settings)
    try:
        a, b = (server.url for server in group.all)
        with browser(a) as ana, browser(b) as ben:
            assert ana.post("/api/playnow", json={"game": "eight_ball"}).json()["status"] == (
                "waiting"
            )
            assert ben.post("/api/playnow", json={"game": "nine_ball"}).json()["status"] == (
                "waiting"
            )
            offered = ana.get("/api/playnow", params={"wait": 10}).json()
            assert offered["status"] == "waiting" and offered["computer"] == "amateur"
            taken = ana.post("/api/playnow/computer").json()
            assert taken["status"] == "matched" and not taken["room"]["ranked"]
            room = httpx.get(f"{b}/api/rooms/{taken['room']['room_id']}", timeout=20).json()
            assert room["players"][1] == "Computer (amateur)"
            assert ben.delete("/api/playnow").json()["status"] == "idle"
            # Ben left: a newcomer on the other process waits alone instead of meeting him.
            with browser(a) as cy:
                assert cy.post("/api/playnow", json={"game": "nine_ball"}).json()["status"] == (
                    "waiting"
                )
                assert ben.post("/api/playnow", json={"game": "nine_ball"}).json()["status"] in (
                    "waiting",
                    "matched",
                )
                met = cy.get("/api/playnow", params={"wait": 10}).json()
                assert met["status"] == "matched" and met["room"]["ranked"]
                assert ben.get("/api/playnow").json()["room"]["room_id"] == met["room"]["room_id"]
    finally:
        for server in group.all:
            server.stop()


def stored(database_url: str, room_id: str, within: float = 20.0) -> None:
    """Wait until the store holds what a process taking the room over reads: the room with
    both seats and its match, and the ranked record. The owner queues those writes, and a
    kill -9 loses whatever is still queued."""
    db = Database(database_url)
    last: dict[str, object] = {}  # what it read last, for the failure message

    def held() -> bool:
        snap = db.run(lambda repo: repo.room(room_id))
        ranked = db.run(lambda repo: PlayerRows(repo).ranked(room_id))
        last.update(room=None if snap is None else snap.data, ranked=ranked)
        if snap is None or ranked is None:
            return False
        return all(snap.data["seats"]) and snap.data["match_id"] is not None

    try:
        waiting.until(held, within, lambda: f"room {room_id} not stored; last read {last}")
    finally:
        db.close()


def owner_moved(base: str, room_id: str, old_url: str, within: float = 20.0) -> str:
    """Ask `base` about the room until another process plays it: its new `ws_url`."""
    deadline = time.monotonic() + within
    while time.monotonic() < deadline:
        reply = httpx.get(f"{base}/api/rooms/{room_id}", timeout=10)
        if reply.status_code == 200 and reply.json()["ws_url"] != old_url:
            return reply.json()["ws_url"]
        time.sleep(0.2)
    raise AssertionError("the room was not taken over in time")


def test_a_ranked_room_taken_over_after_its_server_died_is_still_rated(
    redis: RedisServer,  # noqa: F811
    postgres: PostgresServer,  # noqa: F811
    tmp_path: Path,
):
    database_url = postgres.create_database()
    settings = {"database_url": database_url, "rack_seed": EIGHT_BALL}
    group = ServerSet.start(2, redis.url, tmp_path, settings)
    try:
        a, b = group.all
        with browser(a.url) as ana, browser(b.url) as ben:
            ana.post("/api/playnow", json={"game": "eight_ball"})
            ben.post("/api/playnow", json={"game": "eight_ball"})
            seat_a = ana.get("/api/playnow", params={"wait": 10}).json()["room"]
            seat_b = ben.get("/api/playnow", params={"wait": 10}).json()["room"]
            room_id = seat_a["room_id"]
            old_url = httpx.get(f"{a.url}/api/rooms/{room_id}", timeout=10).json()["ws_url"]
            owner = group.by_url(old_url)
            (survivor,) = group.others(owner)
            stored(database_url, room_id)  # then kill -9
            owner.kill()
            new_url = owner_moved(survivor.url, room_id, old_url)
            tokens = {s["seat"]: s["token"] for s in (seat_a, seat_b)}
            over = asyncio.run(visit_and_concede(new_url, tokens[0], tokens[1]))
            assert over["match"]["match_winner"] == 0
            survivor_ana = httpx.Client(base_url=survivor.url, headers=ana.headers, timeout=20)
            with survivor_ana:
                deadline = time.monotonic() + 10
                while (mine := survivor_ana.get("/api/players/me").json())["recent"] == []:
                    assert time.monotonic() < deadline, "the ranked result was not rated"
                    time.sleep(0.2)
        (result,) = mine["recent"]
        assert result["won"] == (seat_a["seat"] == 0)  # seat 0 won
        # 8-ball, 9-ball, snooker, three-cushion
        assert [r["games"] for r in mine["ratings"]] == [1, 0, 0, 0]
    finally:
        for server in group.all:
            server.stop()
