"""One set of Alembic migrations for both backends: a new database gets exactly the schema
of `server/store/schema.py`, a second start changes nothing, and a SQLite file written
before Alembic (schema counted in `PRAGMA user_version`) is upgraded keeping every row."""

from __future__ import annotations

import sqlite3
from pathlib import Path

import pytest
from alembic.autogenerate import compare_metadata
from alembic.runtime.migration import MigrationContext
from sqlalchemy import create_engine, inspect

from server.store import Database
from server.store.backend import database_url
from server.store.migrate import current, head
from server.store.schema import metadata

# The schema as the store before Alembic wrote it, migration by migration (copied from
# that release's schema.py): the files people have on disk.
BEFORE_ALEMBIC = (
    """
    CREATE TABLE matches (
        id INTEGER PRIMARY KEY, room_id TEXT NOT NULL, kind TEXT NOT NULL,
        players TEXT NOT NULL, race_to INTEGER NOT NULL, status TEXT NOT NULL,
        score TEXT NOT NULL, winner INTEGER, reason TEXT, started_at REAL NOT NULL,
        finished_at REAL
    );
    CREATE INDEX matches_recent ON matches (started_at DESC, id DESC);
    CREATE INDEX matches_room ON matches (room_id);
    CREATE TABLE games (
        match_id INTEGER NOT NULL REFERENCES matches (id), n INTEGER NOT NULL,
        winner INTEGER, reason TEXT, cause TEXT NOT NULL, score TEXT NOT NULL,
        finished_at REAL NOT NULL, PRIMARY KEY (match_id, n)
    );
    CREATE TABLE shots (
        match_id INTEGER NOT NULL REFERENCES matches (id), n INTEGER NOT NULL,
        room_shot INTEGER NOT NULL, game INTEGER NOT NULL, seat INTEGER NOT NULL,
        shot TEXT NOT NULL, table_geom TEXT NOT NULL, balls TEXT NOT NULL,
        outcome TEXT NOT NULL, played_at REAL NOT NULL,
        PRIMARY KEY (match_id, n), UNIQUE (match_id, room_shot)
    );
    CREATE TABLE rooms (
        room_id TEXT PRIMARY KEY, snapshot TEXT NOT NULL, updated_at REAL NOT NULL
    );
    """,
    """
    ALTER TABLE shots ADD COLUMN engine TEXT;
    ALTER TABLE shots ADD COLUMN motion BLOB;
    """,
)
STARTED = 1795700000.0 + 1 / 3
SHOT = '{"angle":0.30000000000000004,"speed":8.999999999999998,"tip":[0.1,-0.1]}'


def old_file(path: Path, version: int) -> None:
    """A database as the release before Alembic left it at `user_version` = `version`,
    with a finished match of one game and two shots, and a saved room."""
    conn = sqlite3.connect(path, isolation_level=None)
    for number, script in enumerate(BEFORE_ALEMBIC[:version], start=1):
        conn.executescript(f"BEGIN;\n{script}\nPRAGMA user_version = {number};\nCOMMIT;")
    conn.execute(
        "INSERT INTO matches VALUES (4, 'room', 'nine_ball', '[\"Ana\",\"Ben\"]', 1, "
        "'finished', '[1,0]', 0, 'Ana won.', ?, ?)",
        (STARTED, STARTED + 60),
    )
    for n in (1, 2):
        conn.execute(
            "INSERT INTO shots (match_id, n, room_shot, game, seat, shot, table_geom, balls, "
            "outcome, played_at) VALUES (4, ?, ?, 1, 0, ?, '[2.54]', '{}', '{}', ?)",
            (n, n + 10, SHOT, STARTED + n),
        )
    conn.execute("INSERT INTO games VALUES (4, 1, 0, 'Ana won.', 'shot', '[1,0]', ?)", (STARTED,))
    conn.execute("INSERT INTO rooms VALUES ('room', '{\"v\":1}', ?)", (STARTED,))
    conn.close()


def schema_differences(target: str | Path) -> list:
    engine = create_engine(database_url(target))
    try:
        with engine.connect() as conn:
            return compare_metadata(MigrationContext.configure(conn), metadata)
    finally:
        engine.dispose()


def test_a_new_database_gets_the_schema_of_the_code_and_a_restart_changes_nothing(
    target: str | Path,
) -> None:
    Database(target).close()
    Database(target).close()  # a second start: already at the newest revision
    assert schema_differences(target) == []
    engine = create_engine(database_url(target))
    with engine.connect() as conn:
        assert current(conn) == head()
        tables = set(inspect(conn).get_table_names())
    engine.dispose()
    assert {"matches", "games", "shots", "rooms", "room_owners", "counters"} <= tables


@pytest.mark.parametrize("version", [1, 2])
def test_a_file_from_before_alembic_is_upgraded_keeping_every_row(
    tmp_path: Path, version: int
) -> None:
    path = tmp_path / "old.db"
    old_file(path, version)
    db = Database(path)
    try:
        match = db.run(lambda r: r.match(4))
        shots = db.run(lambda r: r.shots(4))
        games = db.run(lambda r: r.games(4))
        rooms = db.run(lambda r: r.rooms())
        # the store goes on from where the old one stopped: ids and shot numbers
        assert db.run(lambda r: r.last_match_id()) == 4
        assert db.run(lambda r: r.reserve_match_ids(2)) == range(5, 7)
        again = db.run(lambda r: r.record_shot(4, 11, 1, 0, {}, [], {}, {}))
        third = db.run(lambda r: r.record_shot(4, 13, 1, 1, {}, [], {}, {}, engine="2"))
    finally:
        db.close()
    assert match is not None
    assert (match.status, match.score, match.winner, match.games, match.shots) == (
        "finished",
        [1, 0],
        0,
        1,
        2,
    )
    assert (match.started_at.hex(), match.finished_at) == (STARTED.hex(), STARTED + 60)
    assert [(s.n, s.room_shot, s.played_at, s.engine) for s in shots] == [
        (1, 11, STARTED + 1, None),
        (2, 12, STARTED + 2, None),
    ]
    assert shots[0].shot == {"angle": 0.1 + 0.2, "speed": 8.999999999999998, "tip": [0.1, -0.1]}
    assert [(g.n, g.score) for g in games] == [(1, [1, 0])]
    assert [(r.room_id, r.data, r.updated_at) for r in rooms] == [("room", {"v": 1}, STARTED)]
    assert (again, third) == (1, 3)
    # the same tables, columns, keys and indexes, spelled as the old release did: times
    # REAL (DOUBLE in new files; on SQLite both are the same 8-byte float), primary keys
    # without NOT NULL, the unique (match_id, room_shot) unnamed
    found = {
        (d[0], d[2], d[3]) if d[0].startswith("modify") else (d[0], d[1].table.name, None)
        for diff in schema_differences(path)
        for d in (diff if isinstance(diff, list) else [diff])
    }
    times = {("games", "finished_at"), ("matches", "started_at"), ("matches", "finished_at")}
    times |= {("rooms", "updated_at"), ("shots", "played_at")}
    assert found == {("modify_type", t, c) for t, c in times} | {
        ("modify_nullable", "matches", "id"),
        ("modify_nullable", "rooms", "room_id"),
        ("add_constraint", "shots", None),
    }
