"""A lock on the database delays the history, never loses it; and nothing about a shot is
public before its members have seen it."""

from __future__ import annotations

import os
import sqlite3
import threading
import time
from collections.abc import Iterator
from pathlib import Path

import pytest
from fastapi.testclient import TestClient
from sqlalchemy.exc import OperationalError

from server.app import create_app
from server.config import Settings
from server.rooms import SeedSource
from server.store import Database
from tests.support.rooms import connect

pytestmark = pytest.mark.timeout(120)
TABLE = [2.54, 1.27, 0.028575, 0.114, 0.127]


@pytest.mark.slow  # many seconds: not in scripts/test --quick
def test_writes_wait_out_a_12_second_lock_in_order(tmp_path: Path):
    db = Database(tmp_path / "pool.db")
    db.run(lambda repo: repo.start_match(1, "room", "practice", ["Ana"], 1))
    holder = sqlite3.connect(tmp_path / "pool.db", isolation_level=None, check_same_thread=False)
    holder.execute("BEGIN EXCLUSIVE")  # another process holds the file
    released = threading.Event()

    def release() -> None:
        time.sleep(12.0)
        holder.execute("COMMIT")
        released.set()

    threading.Thread(target=release, daemon=True).start()
    for n in range(1, 6):
        db.write(
            lambda repo, n=n: repo.record_shot(
                1,
                n,
                1,
                0,
                {"angle": 0.0, "speed": 1.0, "tip": [0.0, 0.0]},
                TABLE,
                {"ids": []},
                {"n": n},
            ),
            "record shot",
        )
        db.write(lambda repo, n=n: repo.save_room("room", f'{{"after_shot":{n}}}'), "save room")
    shots = db.run(lambda repo: repo.shots(1))
    rooms = db.run(lambda repo: repo.rooms())
    db.close()
    assert released.is_set()
    assert [(s.n, s.outcome) for s in shots] == [(n, {"n": n}) for n in range(1, 6)]
    assert [r.data for r in rooms] == [{"after_shot": 5}]


@pytest.mark.slow  # many seconds: not in scripts/test --quick
def test_a_process_starting_while_another_holds_the_new_file_waits_for_it(tmp_path: Path):
    """Two servers starting at once on one new SQLite file: whichever connects second is
    told "locked" when it turns the journal to WAL. It tries again, not exits."""
    holder = sqlite3.connect(tmp_path / "pool.db", isolation_level=None, check_same_thread=False)
    holder.execute("BEGIN EXCLUSIVE")  # the other process, creating the file
    waits: list[float] = []

    def sleep(seconds: float) -> None:  # the store's wait between tries: the other is done
        waits.append(seconds)
        holder.execute("COMMIT")

    db = Database(tmp_path / "pool.db", sleep=sleep)
    try:
        assert db.run(lambda repo: repo.rooms()) == []  # opened and migrated
        assert db.run(lambda repo: repo.conn.execute("PRAGMA journal_mode").fetchone()) == ("wal",)
    finally:
        db.close()
        holder.close()
    assert waits == [0.05]  # one refused try (after the driver's own 5 s wait), then open


def test_a_file_that_cannot_be_migrated_is_not_left_open(tmp_path: Path):
    """A store that fails to start gives its connections back: a caller that goes on (a
    test, a tool) keeps no handle on the file."""
    path = tmp_path / "pool.db"
    other = sqlite3.connect(path)  # another program's file, with a table of our name
    other.execute("CREATE TABLE matches (x)")
    other.commit()
    other.close()

    def handles() -> int:
        fds = Path("/proc/self/fd")
        return sum(1 for fd in fds.iterdir() if _points_to(fd, path))

    with pytest.raises(OperationalError, match="already exists"):
        Database(path, start_retry=0.0)
    assert handles() == 0


def _points_to(fd: Path, path: Path) -> bool:
    try:
        return Path(os.readlink(fd)) == path
    except OSError:  # closed since it was listed
        return False


@pytest.fixture
def slow_client(tmp_path: Path) -> Iterator[TestClient]:
    settings = Settings(web_dir=tmp_path, db_path=tmp_path / "pool.db", pace=1.0)
    with TestClient(create_app(settings, seeds=SeedSource.fixed(5))) as c:
        yield c


@pytest.mark.slow  # many seconds: not in scripts/test --quick
def test_a_shot_is_public_only_once_it_has_been_shown(slow_client: TestClient):
    client = slow_client
    room_id = client.post("/api/rooms", json={"game": "eight_ball"}).json()["room_id"]
    tokens = [
        client.post(f"/api/rooms/{room_id}/join", json={"name": n}).json()["token"]
        for n in ("Ana", "Ben")
    ]
    with connect(client, room_id, tokens[0]) as ana:
        while ana.receive_json()["type"] != "presence":
            pass
        ana.send_json({"type": "shoot", "angle": 0.0, "speed": 9.0})
        while ana.receive_json()["type"] != "motion":
            pass  # the break is being shown now
        during = client.get("/api/matches/1").json()
        replay = client.get("/api/matches/1/shots/1/replay")
        listed = client.get("/api/rooms").json()["rooms"][0]
        assert during["shots"] == [] and replay.status_code == 404
        assert listed["score"] == [0, 0]
        while ana.receive_json()["type"] != "shot_result":
            pass
        after = client.get("/api/matches/1").json()
    assert [s["n"] for s in after["shots"]] == [1]
