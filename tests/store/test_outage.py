"""PostgreSQL out of reach (restarting, a network cut) delays the history, never loses or
reorders it: a write is tried again on a new connection until the server is back. The
store waits through an injected `sleep` and `clock`, so "10 s down" costs the test no ten
real seconds; the server is really stopped and started again. A read awaited from the
event loop does not wait with those writes: it gives up at its own deadline, and the API
answers `503 unavailable`, never a hang or a 500."""

from __future__ import annotations

import asyncio
from collections.abc import Iterator
from pathlib import Path

import pytest
from fastapi.testclient import TestClient
from sqlalchemy.exc import OperationalError

from server.app import create_app
from server.store import Database, Repository, StoreUnavailable
from tests.support.postgres import PostgresServer, running_postgres
from tests.support.settings import settings_in

pytestmark = [pytest.mark.timeout(120), pytest.mark.postgres]
TABLE = [2.54, 1.27, 0.028575, 0.114, 0.127]


class StoreTime:
    """The store's clock: it moves only when the store sleeps. `then` runs once the clock
    passes `at` (the server comes back)."""

    def __init__(self) -> None:
        self.now = 0.0
        self.waits: list[float] = []
        self.at = float("inf")
        self.then = lambda: None

    def clock(self) -> float:
        return self.now

    def sleep(self, seconds: float) -> None:
        self.waits.append(seconds)
        self.now += seconds
        if self.now >= self.at:
            self.at = float("inf")
            self.then()


@pytest.fixture(scope="module")
def server() -> Iterator[PostgresServer]:
    """A server of these tests' own: they stop it and start it again."""
    with running_postgres() as pg:
        yield pg
        assert pg.running()  # each test leaves it up


def record(repo: Repository, n: int) -> int:
    shot = {"angle": 0.0, "speed": 1.0, "tip": [0.0, 0.0]}
    return repo.record_shot(1, n, 1, 0, shot, TABLE, {"ids": []}, {"n": n}, epoch=1)


def test_writes_wait_out_ten_seconds_without_postgresql_in_order(server: PostgresServer):
    time = StoreTime()
    db = Database(server.create_database(), sleep=time.sleep, clock=time.clock)
    db.run(lambda r: r.start_match(1, "room", "practice", ["Ana"], 1, epoch=1))
    db.run(lambda r: r.save_room("room", '{"after_shot":0}', epoch=1))
    server.stop("immediate")  # gone at once, connections cut, like a crash
    time.at, time.then = 10.0, server.start
    for n in range(1, 6):
        db.write(lambda r, n=n: record(r, n), "record shot")
        db.write(lambda r, n=n: r.save_room("room", f'{{"after_shot":{n}}}', epoch=1), "save")
    shots = db.run(lambda r: r.shots(1))  # queued behind the writes
    rooms = db.run(lambda r: r.rooms())
    db.close()
    assert sum(time.waits) >= 10.0  # the first write waited the outage out
    assert time.waits[:3] == [0.05, 0.1, 0.2] and max(time.waits) == 2.0  # backoff, capped
    assert [(s.n, s.outcome) for s in shots] == [(n, {"n": n}) for n in range(1, 6)]
    assert [r.data for r in rooms] == [{"after_shot": 5}]


def test_a_read_gives_up_after_its_limit_and_the_store_goes_on(server: PostgresServer):
    time = StoreTime()
    url = server.create_database()
    db = Database(url, sleep=time.sleep, clock=time.clock)
    db.run(lambda r: r.save_room("room", "{}"))
    server.stop("immediate")
    with pytest.raises(OperationalError):
        db.submit(lambda r: r.rooms(), retry_for=10.0).result()
    assert 5.0 < time.now <= 10.0
    starting = StoreTime()
    with pytest.raises(OperationalError):  # nor can a process start on it meanwhile:
        Database(url, start_retry=20.0, sleep=starting.sleep, clock=starting.clock)
    assert 15.0 < starting.now <= 20.0  # it tried for its window, then gave up
    server.start()
    assert [r.room_id for r in db.run(lambda r: r.rooms())] == ["room"]
    db.close()


def test_a_read_behind_writes_waiting_out_an_outage_gives_up_at_its_deadline(
    server: PostgresServer,
):
    db = Database(server.create_database(), read_deadline=0.5)
    db.run(lambda r: r.save_room("room", '{"n":0}', epoch=1))
    server.stop("immediate")
    try:
        db.write(lambda r: r.save_room("room", '{"n":1}', epoch=1), "save")  # waits it out
        with pytest.raises(StoreUnavailable):
            asyncio.run(db.call(lambda r: r.rooms()))
        with pytest.raises(StoreUnavailable):  # and a read at the head of the queue too
            asyncio.run(db.call(lambda r: r.match(1)))
    finally:
        server.start()
    assert [r.data for r in asyncio.run(db.call(lambda r: r.rooms()))] == [{"n": 1}]
    db.close()


def test_the_api_answers_503_unavailable_while_postgresql_is_down(
    server: PostgresServer, tmp_path: Path
):
    store = Database(server.create_database(), read_deadline=0.5)
    app = create_app(settings_in(tmp_path), store=store)
    with TestClient(app) as client:
        assert client.get("/api/players/me").status_code == 200  # a profile and its cookie
        server.stop("immediate")
        try:
            replies = [client.get(path) for path in ("/api/players/me", "/api/matches")]
            replies.append(client.get("/api/matches/1"))
            replies.append(client.get("/api/leaderboard/nine_ball"))
        finally:
            server.start()
        assert [r.status_code for r in replies] == [503] * 4
        assert all(r.json()["detail"]["code"] == "unavailable" for r in replies)
        assert client.get("/api/players/me").status_code == 200  # back
