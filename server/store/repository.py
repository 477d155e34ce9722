"""Typed queries over one `sqlite3.Connection` (no ORM). Runs on the store's own thread.

Writes are idempotent where a restart can repeat them: a shot replayed after a restart has
the same room shot id, so it is recorded once (`INSERT OR IGNORE` on a unique key).
"""

from __future__ import annotations

import json
import sqlite3
import time
import zlib

from server.codec import encode

from .records import GameRecord, MatchRecord, RoomSnapshot, ShotRecord

_dump = encode


class Repository:
    def __init__(self, conn: sqlite3.Connection) -> None:
        self.conn = conn

    # ---- matches ----------------------------------------------------------------------

    def last_match_id(self) -> int:
        return int(self.conn.execute("SELECT COALESCE(MAX(id), 0) FROM matches").fetchone()[0])

    def start_match(
        self,
        match_id: int,
        room_id: str,
        kind: str,
        players: list[str],
        race_to: int,
        started_at: float | None = None,
    ) -> None:
        """A new match in `room_id`. The caller picks the id (one process owns the file), so
        it need not wait for the insert to know it."""
        self.conn.execute(
            "INSERT OR IGNORE INTO matches (id, room_id, kind, players, race_to, status, "
            "score, started_at) VALUES (?, ?, ?, ?, ?, 'playing', ?, ?)",
            (
                match_id,
                room_id,
                kind,
                _dump(players),
                race_to,
                _dump([0] * len(players)),
                time.time() if started_at is None else started_at,
            ),
        )

    def update_score(self, match_id: int, score: list[int]) -> None:
        self.conn.execute("UPDATE matches SET score = ? WHERE id = ?", (_dump(score), match_id))

    def finish_match(
        self,
        match_id: int,
        score: list[int],
        winner: int | None,
        reason: str | None,
        status: str = "finished",
        finished_at: float | None = None,
    ) -> None:
        """Close the match record (once: a finished match stays as it was first closed)."""
        self.conn.execute(
            "UPDATE matches SET status = ?, score = ?, winner = ?, reason = ?, finished_at = ?"
            " WHERE id = ? AND status = 'playing'",
            (
                status,
                _dump(score),
                winner,
                reason,
                time.time() if finished_at is None else finished_at,
                match_id,
            ),
        )

    def match(self, match_id: int) -> MatchRecord | None:
        rows = self._matches("WHERE m.id = ?", (match_id,))
        return rows[0] if rows else None

    def recent_matches(self, limit: int = 20, status: str | None = None) -> list[MatchRecord]:
        """Newest first; `status` filters ("playing", "finished", "abandoned")."""
        if status is None:
            return self._matches("ORDER BY m.started_at DESC, m.id DESC LIMIT ?", (limit,))
        return self._matches(
            "WHERE m.status = ? ORDER BY m.started_at DESC, m.id DESC LIMIT ?", (status, limit)
        )

    def _matches(self, where: str, params: tuple) -> list[MatchRecord]:
        sql = (
            "SELECT m.id, m.room_id, m.kind, m.players, m.race_to, m.status, m.score, "
            "m.winner, m.reason, m.started_at, m.finished_at, "
            "(SELECT COUNT(*) FROM games g WHERE g.match_id = m.id), "
            "(SELECT COUNT(*) FROM shots s WHERE s.match_id = m.id) "
            f"FROM matches m {where}"
        )
        return [
            MatchRecord(
                r[0],
                r[1],
                r[2],
                json.loads(r[3]),
                r[4],
                r[5],
                json.loads(r[6]),
                r[7],
                r[8],
                r[9],
                r[10],
                r[11],
                r[12],
            )
            for r in self.conn.execute(sql, params)
        ]

    # ---- games ------------------------------------------------------------------------

    def record_game(
        self,
        match_id: int,
        n: int,
        winner: int | None,
        reason: str | None,
        cause: str,
        score: list[int],
        finished_at: float | None = None,
    ) -> None:
        """A finished game (frame) and the match score after it."""
        with self.conn:
            self.conn.execute(
                "INSERT OR IGNORE INTO games (match_id, n, winner, reason, cause, score, "
                "finished_at) VALUES (?, ?, ?, ?, ?, ?, ?)",
                (
                    match_id,
                    n,
                    winner,
                    reason,
                    cause,
                    _dump(score),
                    time.time() if finished_at is None else finished_at,
                ),
            )
            self.update_score(match_id, score)

    def games(self, match_id: int) -> list[GameRecord]:
        rows = self.conn.execute(
            "SELECT match_id, n, winner, reason, cause, score, finished_at FROM games "
            "WHERE match_id = ? ORDER BY n",
            (match_id,),
        )
        return [GameRecord(r[0], r[1], r[2], r[3], r[4], json.loads(r[5]), r[6]) for r in rows]

    # ---- shots ------------------------------------------------------------------------

    def record_shot(
        self,
        match_id: int,
        room_shot: int,
        game: int,
        seat: int,
        shot: dict,
        table: list[float],
        balls: dict,
        outcome: dict,
        played_at: float | None = None,
        engine: str | None = None,
        motion: str | None = None,
    ) -> int:
        """Store a shot as number n+1 of its match; a repeat of the same room shot is ignored.
        `engine` is the engine version that played it, `motion` the streamed messages
        (compressed here, on the store's thread). Returns the shot's number in the match."""
        packed = None if motion is None else zlib.compress(motion.encode(), 6)
        with self.conn:
            self.conn.execute(
                "INSERT OR IGNORE INTO shots (match_id, n, room_shot, game, seat, shot, "
                "table_geom, balls, outcome, played_at, engine, motion) VALUES (?, "
                "(SELECT COALESCE(MAX(n), 0) + 1 FROM shots WHERE match_id = ?), "
                "?, ?, ?, ?, ?, ?, ?, ?, ?, ?)",
                (
                    match_id,
                    match_id,
                    room_shot,
                    game,
                    seat,
                    _dump(shot),
                    _dump(table),
                    _dump(balls),
                    _dump(outcome),
                    time.time() if played_at is None else played_at,
                    engine,
                    packed,
                ),
            )
            row = self.conn.execute(
                "SELECT n FROM shots WHERE match_id = ? AND room_shot = ?", (match_id, room_shot)
            ).fetchone()
        return int(row[0])

    def shots(self, match_id: int) -> list[ShotRecord]:
        """Every shot of the match, without its motion (a list has no use for it)."""
        return self._shots("WHERE match_id = ? ORDER BY n", (match_id,), motion=False)

    def shot(self, match_id: int, n: int) -> ShotRecord | None:
        rows = self._shots("WHERE match_id = ? AND n = ?", (match_id, n), motion=True)
        return rows[0] if rows else None

    def _shots(self, where: str, params: tuple, motion: bool) -> list[ShotRecord]:
        sql = (
            "SELECT match_id, n, room_shot, game, seat, shot, table_geom, balls, outcome, "
            f"played_at, engine, {'motion' if motion else 'NULL'} FROM shots {where}"
        )
        return [
            ShotRecord(
                r[0],
                r[1],
                r[2],
                r[3],
                r[4],
                json.loads(r[5]),
                json.loads(r[6]),
                json.loads(r[7]),
                json.loads(r[8]),
                r[9],
                r[10],
                None if r[11] is None else zlib.decompress(r[11]).decode(),
            )
            for r in self.conn.execute(sql, params)
        ]

    # ---- live rooms -------------------------------------------------------------------

    def save_room(self, room_id: str, snapshot_json: str) -> None:
        self.conn.execute(
            "INSERT INTO rooms (room_id, snapshot, updated_at) VALUES (?, ?, ?) "
            "ON CONFLICT (room_id) DO UPDATE SET snapshot = excluded.snapshot, "
            "updated_at = excluded.updated_at",
            (room_id, snapshot_json, time.time()),
        )

    def delete_room(self, room_id: str) -> None:
        self.conn.execute("DELETE FROM rooms WHERE room_id = ?", (room_id,))

    def rooms(self) -> list[RoomSnapshot]:
        rows = self.conn.execute(
            "SELECT room_id, snapshot, updated_at FROM rooms ORDER BY updated_at"
        )
        return [RoomSnapshot(r[0], json.loads(r[1]), r[2]) for r in rows]
