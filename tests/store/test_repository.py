"""The repository and the database thread, on SQLite and PostgreSQL: round trips, exact
floats, idempotent writes."""

from __future__ import annotations

import asyncio
import json
import math
import threading
from pathlib import Path

import numpy as np
import pytest
from sqlalchemy import text
from sqlalchemy.exc import IntegrityError

from server.engine import BallSet, Shot, Table, rack, simulate
from server.rooms.replay import resimulate
from server.store import Database, Repository, StaleOwner

TABLE = Table.pool("9ft")
PLAYED = 1795700416.3912654 + 1 / 3  # a time with a long binary expansion
TABLE_FIELDS = [TABLE.length, TABLE.width, TABLE.ball_radius, TABLE.corner_mouth, TABLE.side_mouth]


def awkward_balls() -> BallSet:
    """A rack nudged by values with long binary expansions (and a moving ball)."""
    balls = rack("eight_ball", TABLE, seed=3)
    balls.positions += np.array([[math.pi * 1e-9, -1 / 3 * 1e-7]])
    balls.velocities[1] = (1e-300, -0.1)
    return balls


def test_match_game_and_shot_round_trip_exactly(db: Database) -> None:
    balls = awkward_balls()
    shot = {"angle": 0.1 + 0.2, "speed": 8.999999999999998, "tip": [1 / 3 * 0.5, -0.1]}
    outcome = {"shooter": 0, "pocketed": [3], "message": "Ana pockets 3."}

    def write(repo: Repository) -> int:
        repo.start_match(7, "room-a", "eight_ball", ["Ana", "Ben"], 3, started_at=100.0)
        n1 = repo.record_shot(
            7, 1, 1, 0, shot, TABLE_FIELDS, balls.to_dict(), outcome, played_at=PLAYED
        )
        n2 = repo.record_shot(7, 2, 1, 1, shot, TABLE_FIELDS, balls.to_dict(), outcome)
        again = repo.record_shot(7, 1, 1, 0, shot, TABLE_FIELDS, balls.to_dict(), outcome)
        assert (n1, n2, again) == (1, 2, 1)  # the same room shot is stored once
        repo.record_game(7, 1, 1, "Ben pocketed the 8.", "shot", [0, 1])
        repo.record_game(7, 1, 0, "repeat", "shot", [9, 9])  # ignored: game 1 is recorded
        repo.finish_match(7, [0, 1], 1, "Ben reached 1.", finished_at=200.0)
        repo.finish_match(7, [5, 5], 0, "late", status="abandoned")  # already closed
        return repo.last_match_id()

    assert db.run(write) == 7
    match = db.run(lambda repo: repo.match(7))
    assert match is not None
    assert (match.status, match.score, match.winner, match.reason) == (
        "finished",
        [0, 1],
        1,
        "Ben reached 1.",
    )
    assert (match.games, match.shots, match.started_at, match.finished_at) == (1, 2, 100.0, 200.0)
    assert match.winner is not None and match.players[match.winner] == "Ben"
    games = db.run(lambda repo: repo.games(7))
    assert [(g.n, g.winner, g.score) for g in games] == [(1, 1, [0, 1])]
    stored = db.run(lambda repo: repo.shot(7, 1))
    assert stored is not None and stored.shot == shot and stored.outcome == outcome
    assert stored.played_at.hex() == PLAYED.hex()  # a time reads back bit for bit too
    back = BallSet.from_dict(stored.balls)
    for name in ("positions", "velocities", "spins", "phases"):
        assert getattr(back, name).tobytes() == getattr(balls, name).tobytes()
    assert db.run(lambda repo: repo.shot(7, 3)) is None
    assert db.run(lambda repo: repo.match(8)) is None


def test_a_stored_shot_simulates_to_the_same_result_bit_for_bit(db: Database) -> None:
    balls = rack("nine_ball", TABLE, seed=11)
    shot = Shot(0.0123456789, 8.7654321, (0.1, -0.2))
    original = simulate(TABLE, balls, shot)
    db.run(lambda repo: repo.start_match(1, "r", "nine_ball", ["A", "B"], 1))
    db.run(
        lambda repo: repo.record_shot(
            1,
            1,
            1,
            0,
            {"angle": shot.angle, "speed": shot.speed, "tip": list(shot.tip)},
            TABLE_FIELDS,
            balls.to_dict(),
            {},
        )
    )
    stored = db.run(lambda repo: repo.shot(1, 1))
    assert stored is not None
    again = resimulate(stored)
    assert again.frames.positions.tobytes() == original.frames.positions.tobytes()
    assert again.frames.cels.tobytes() == original.frames.cels.tobytes()
    assert again.final.positions.tobytes() == original.final.positions.tobytes()
    assert [(e.time, e.kind, e.ids) for e in again.events] == [
        (e.time, e.kind, e.ids) for e in original.events
    ]


def test_recent_matches_newest_first_with_a_status_filter(db: Database) -> None:
    def write(repo: Repository) -> None:
        for i in range(1, 6):
            repo.start_match(i, f"room{i}", "eight_ball", ["A", "B"], 1, started_at=float(i))
        repo.finish_match(2, [1, 0], 0, "A reached 1.")
        repo.finish_match(4, [0, 0], None, "closed", status="abandoned")

    db.run(write)
    assert [m.id for m in db.run(lambda r: r.recent_matches(3))] == [5, 4, 3]
    assert [m.id for m in db.run(lambda r: r.recent_matches(10, "finished"))] == [2]
    assert [m.id for m in db.run(lambda r: r.recent_matches(10, "playing"))] == [5, 3, 1]


def test_rooms_save_overwrite_delete_and_survive_reopening(target: str | Path) -> None:
    first = Database(target)
    first.submit(lambda r: r.save_room("a", json.dumps({"v": 1})))
    first.submit(lambda r: r.save_room("b", json.dumps({"v": 2})))
    first.submit(lambda r: r.save_room("a", json.dumps({"v": 3})))
    first.submit(lambda r: r.delete_room("b"))
    first.close()  # waits for the queue
    second = Database(target)
    try:
        rooms = second.run(lambda r: r.rooms())
        assert [(s.room_id, s.data) for s in rooms] == [("a", {"v": 3})]
        assert second.run(lambda r: r.room("a")) == rooms[0]
        assert second.run(lambda r: r.room("b")) is None
    finally:
        second.close()


def test_call_from_the_event_loop_and_errors_come_back(db: Database) -> None:
    async def main() -> None:
        assert await db.call(lambda r: r.last_match_id()) == 0
        bad = text("INSERT INTO rooms VALUES (NULL, NULL, 0)")
        with pytest.raises(IntegrityError):
            await db.call(lambda r: r.run_in_transaction(bad))
        assert await db.call(lambda r: r.rooms()) == []  # the thread survived the error

    asyncio.run(main())
    db.close()
    with pytest.raises(RuntimeError):
        db.run(lambda r: r.rooms())


def test_a_shot_keeps_its_engine_version_and_motion(db: Database) -> None:
    motion = "".join(f'{i / 20!r} frame {{"shot":1,"tick":{i * 6}}}\n' for i in range(200))

    def write(repo: Repository) -> None:
        repo.start_match(1, "room", "eight_ball", ["Ana", "Ben"], 1)
        repo.record_shot(
            1,
            1,
            1,
            0,
            {"angle": 0.0, "speed": 1.0, "tip": [0.0, 0.0]},
            TABLE_FIELDS,
            awkward_balls().to_dict(),
            {},
            engine="1+abc",
            motion=motion,
        )

    db.run(write)
    stored = db.run(lambda repo: repo.shot(1, 1))
    listed = db.run(lambda repo: repo.shots(1))
    size = db.run(lambda r: r.run_in_transaction(text("SELECT length(motion) FROM shots")))
    assert stored is not None and (stored.engine, stored.motion) == ("1+abc", motion)
    assert [(s.engine, s.motion) for s in listed] == [("1+abc", None)]  # lists skip motion
    assert size < len(motion) / 4  # stored compressed (a blob; bytea on PostgreSQL)


def test_queued_writes_share_a_transaction_yet_fail_alone(target: str | Path) -> None:
    """Writes queued together run as one transaction (one commit), each in a savepoint: a
    refused or broken write fails alone, the others are stored, in order."""
    db = Database(target, batch=64)
    gate = threading.Event()
    db.submit(lambda _r: gate.wait(30))  # holds the store thread while the writes queue
    shot = {"angle": 0.0, "speed": 1.0, "tip": [0.0, 0.0]}
    futures = [
        db.write(lambda r: r.start_match(1, "room", "practice", ["Ana"], 1, epoch=2), "start"),
        db.write(lambda r: r.record_shot(1, 1, 1, 0, shot, [], {}, {}, epoch=2), "shot 1"),
        db.write(lambda r: r.save_room("room", "{}", epoch=1), "stale"),  # refused
        db.write(lambda r: r.record_shot(9, 1, 1, 0, shot, [], {}, {}), "no match"),  # broken
        db.write(lambda r: r.record_shot(1, 2, 1, 0, shot, [], {}, {}, epoch=2), "shot 2"),
    ]
    gate.set()
    assert [f.result(30) for f in (futures[0], futures[1], futures[4])] == [None, 1, 2]
    with pytest.raises(StaleOwner):
        futures[2].result(30)
    with pytest.raises(IntegrityError):
        futures[3].result(30)
    assert [s.room_shot for s in db.run(lambda r: r.shots(1))] == [1, 2]
    assert db.run(lambda r: r.rooms()) == []
    assert db.run(lambda r: r.room_epoch("room")) == 2
    db.close()
