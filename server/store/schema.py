"""The schema as numbered migrations; `PRAGMA user_version` says how many have run.

Add a migration at the end to change the schema; never edit one that has shipped.
JSON columns hold floats as Python writes them (`repr`), which read back bit for bit.
"""

from __future__ import annotations

import sqlite3

MIGRATIONS: tuple[str, ...] = (
    """
    CREATE TABLE matches (
        id          INTEGER PRIMARY KEY,
        room_id     TEXT    NOT NULL,
        kind        TEXT    NOT NULL,
        players     TEXT    NOT NULL,              -- JSON list of names, seat order
        race_to     INTEGER NOT NULL,
        status      TEXT    NOT NULL,              -- playing | finished | abandoned
        score       TEXT    NOT NULL,              -- JSON list, games won per seat
        winner      INTEGER,                       -- seat
        reason      TEXT,
        started_at  REAL    NOT NULL,
        finished_at REAL
    );
    CREATE INDEX matches_recent ON matches (started_at DESC, id DESC);
    CREATE INDEX matches_room ON matches (room_id);

    CREATE TABLE games (                           -- players call a game a frame
        match_id    INTEGER NOT NULL REFERENCES matches (id),
        n           INTEGER NOT NULL,              -- 1, 2, ... within the match
        winner      INTEGER,
        reason      TEXT,
        cause       TEXT    NOT NULL,              -- shot | timeout | concede | forfeit
        score       TEXT    NOT NULL,              -- JSON, after this game
        finished_at REAL    NOT NULL,
        PRIMARY KEY (match_id, n)
    );

    CREATE TABLE shots (
        match_id    INTEGER NOT NULL REFERENCES matches (id),
        n           INTEGER NOT NULL,              -- 1, 2, ... within the match
        room_shot   INTEGER NOT NULL,              -- the room's shot id (live `shot` field)
        game        INTEGER NOT NULL,              -- game number within the match
        seat        INTEGER NOT NULL,
        shot        TEXT    NOT NULL,              -- JSON {angle, speed, tip}
        table_geom  TEXT    NOT NULL,              -- JSON Table constructor arguments
        balls       TEXT    NOT NULL,              -- JSON BallSet.to_dict() before the shot
        outcome     TEXT    NOT NULL,              -- JSON Outcome.to_dict()
        played_at   REAL    NOT NULL,
        PRIMARY KEY (match_id, n),
        UNIQUE (match_id, room_shot)
    );

    CREATE TABLE rooms (                           -- live rooms, for restart recovery
        room_id     TEXT    PRIMARY KEY,
        snapshot    TEXT    NOT NULL,              -- JSON, see server/rooms/snapshot.py
        updated_at  REAL    NOT NULL
    );
    """,
    """
    -- which engine played each shot, and the motion every member was shown (zlib of
    -- protocol.plan.motion_text): a replay shows that, not a re-simulation by a newer
    -- engine. Older rows have neither.
    ALTER TABLE shots ADD COLUMN engine TEXT;
    ALTER TABLE shots ADD COLUMN motion BLOB;
    """,
)


def migrate(conn: sqlite3.Connection) -> int:
    """Run the migrations this database has not seen yet; returns the schema version."""
    version = conn.execute("PRAGMA user_version").fetchone()[0]
    for number, script in enumerate(MIGRATIONS[version:], start=version + 1):
        conn.executescript(f"BEGIN;\n{script}\nPRAGMA user_version = {number};\nCOMMIT;")
    return len(MIGRATIONS)
