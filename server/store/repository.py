"""Typed queries (SQLAlchemy Core) on the store's one connection, on the store's thread.

Each public method is one transaction (`transaction()` groups several). Writes are
idempotent where a restart or a failover can repeat them: a shot played again has the same
room shot id and is recorded once, a game once, a match closed once. Room-scoped writes
take an optional fencing `epoch` (see `claim_room`): when a higher epoch is stored for the
room, the write raises `StaleOwner` and changes nothing, checked in the same transaction
with the owner's row locked. The statements themselves are in `statements`.
"""

from __future__ import annotations

import contextlib
import json
import time
import zlib
from collections.abc import Iterator
from typing import Any

from sqlalchemy import Connection, Engine, Row

from server.codec import encode

from .errors import StaleOwner
from .records import GameRecord, MatchRecord, RoomSnapshot, ShotRecord
from .statements import statements

_dump = encode
# zlib's fastest level: the motions of 60 shots (2.8 KB of text on average) took 65 µs each
# to 1.75 KB, against 108 µs to 1.72 KB at the default 6, on the store's thread, which
# shares the server's cores with the loop and the shots. Any level reads back.
MOTION_ZLIB_LEVEL = 1


class Repository:
    def __init__(self, engine: Engine) -> None:
        self.engine = engine
        self.dialect = engine.dialect.name
        self.sql = statements(self.dialect)
        self._connection: Connection | None = None
        self._depth = 0  # nested transaction() calls share the outer one

    # ---- connection and transactions --------------------------------------------------

    @property
    def connection(self) -> Connection:
        """The open connection (opened on first use, again after `reset`)."""
        if self._connection is None:
            self._connection = self.engine.connect()
        return self._connection

    @property
    def conn(self) -> Any:
        """The driver's own connection, for a test that doctors a row by hand."""
        return self.connection.connection.dbapi_connection

    def reset(self) -> None:
        """Drop the connection after a failure; the next call opens a new one."""
        if self._connection is not None:
            with contextlib.suppress(Exception):
                self._connection.close()
        self._connection = None
        self._depth = 0

    def close(self) -> None:
        self.reset()
        self.engine.dispose()

    @contextlib.contextmanager
    def transaction(self, write: bool = True) -> Iterator[Connection]:
        """One transaction around the block (nested calls join it). On SQLite a write
        takes the file's write lock at its start."""
        conn = self.connection
        if self._depth:
            self._depth += 1
            try:
                yield conn
            finally:
                self._depth -= 1
            return
        with conn.begin():
            if self.dialect == "sqlite":
                conn.exec_driver_sql("BEGIN IMMEDIATE" if write else "BEGIN")
            self._depth = 1
            try:
                yield conn
            finally:
                self._depth = 0

    def settle(self, ok: bool) -> None:
        """End a transaction a caller began by using `connection` directly (commit if its
        job succeeded): the connection never idles inside a transaction."""
        if self._connection is not None and self._connection.in_transaction():
            if ok:
                self._connection.commit()
            else:
                self._connection.rollback()

    def run_in_transaction(self, statement: Any) -> Any:
        """Run one hand-written statement (a test's); returns its first value, if any."""
        with self.transaction() as conn:
            result = conn.execute(statement)
            return result.scalar() if result.returns_rows else None

    def _read(self) -> contextlib.AbstractContextManager[Connection]:
        return self.transaction(write=False)

    # ---- room ownership (fencing) -----------------------------------------------------

    def claim_room(self, room_id: str, epoch: int, owner: str = "") -> None:
        """Record that `owner` holds `room_id` at fencing `epoch` (from the lease); the same
        owner may claim its epoch again. Raises `StaleOwner` if a higher epoch is stored,
        or the same epoch by another owner (two owners never share an epoch)."""
        with self.transaction() as conn:
            stored, holder = self._owner_row(conn, room_id, epoch, owner)
            if stored > epoch or (stored == epoch and owner and holder not in ("", owner)):
                raise StaleOwner(room_id, epoch, stored)
            if stored < epoch or holder != owner:
                conn.execute(
                    self.sql.set_owner,
                    {
                        "key_room": room_id,
                        "epoch": epoch,
                        "owner": owner,
                        "claimed_at": time.time(),
                    },
                )

    def room_epoch(self, room_id: str) -> int | None:
        """The highest epoch claimed for the room (None: never claimed)."""
        with self._read() as conn:
            found = conn.scalar(self.sql.read_epoch, {"key_room": room_id})
        return None if found is None else int(found)

    def prune_room_owners(self, before: float) -> int:
        """Forget the owners of rooms gone (no saved room) and last claimed before `before`
        (a wall time, e.g. a day ago): the table stays the size of the live rooms. A stale
        owner paused since then could claim such a room afresh, so keep the window long.
        Returns how many were forgotten."""
        with self.transaction() as conn:
            return int(conn.execute(self.sql.prune_owners, {"key_before": before}).rowcount)

    def _owner_row(self, conn: Connection, room_id: str, epoch: int, owner: str) -> tuple[int, str]:
        """The room's stored epoch and owner, the row locked to the end of the transaction;
        a room never claimed gets a row with `epoch`, so a later lower epoch is refused."""
        key = {"key_room": room_id}
        found = conn.execute(self.sql.owner_epoch, key).first()
        if found is None:
            row = {"room_id": room_id, "epoch": epoch, "owner": owner, "claimed_at": time.time()}
            conn.execute(self.sql.add_owner, row)
            found = conn.execute(self.sql.owner_epoch, key).one()
        return int(found.epoch), str(found.owner)

    def _fence(self, conn: Connection, room_id: str | None, epoch: int | None) -> None:
        if epoch is None or room_id is None:
            return
        stored, _ = self._owner_row(conn, room_id, epoch, "")
        if stored > epoch:
            raise StaleOwner(room_id, epoch, stored)

    def _fence_match(self, conn: Connection, match_id: int, epoch: int | None) -> None:
        if epoch is not None:
            self._fence(conn, conn.scalar(self.sql.match_room, {"key_match": match_id}), epoch)

    # ---- matches ----------------------------------------------------------------------

    def last_match_id(self) -> int:
        with self._read() as conn:
            return int(conn.scalar(self.sql.last_match) or 0)

    def reserve_match_ids(self, count: int) -> range:
        """`count` match ids no other process (sharing this store) will be given: for
        picking ids without waiting on the store, a block at a time."""
        if count < 1:
            raise ValueError("count must be at least 1")
        with self.transaction() as conn:
            value = conn.scalar(self.sql.counter, {"key_name": "match"})
            used = conn.scalar(self.sql.last_match)
            start = max(int(value or 0), int(used or 0)) + 1
            conn.execute(self.sql.set_counter, {"name": "match", "value": start + count - 1})
        return range(start, start + count)

    def start_match(
        self,
        match_id: int,
        room_id: str,
        kind: str,
        players: list[str],
        race_to: int,
        started_at: float | None = None,
        *,
        epoch: int | None = None,
    ) -> None:
        """A new match in `room_id` (a repeat of the id is ignored). The caller picks the
        id (`last_match_id` + 1 in one process, `reserve_match_ids` in several), so it need
        not wait for the insert to know it."""
        row = {
            "id": match_id,
            "room_id": room_id,
            "kind": kind,
            "players": _dump(players),
            "race_to": race_to,
            "status": "playing",
            "score": _dump([0] * len(players)),
            "started_at": time.time() if started_at is None else started_at,
        }
        with self.transaction() as conn:
            self._fence(conn, room_id, epoch)
            conn.execute(self.sql.add_match, row)

    def update_score(self, match_id: int, score: list[int], *, epoch: int | None = None) -> None:
        with self.transaction() as conn:
            self._fence_match(conn, match_id, epoch)
            conn.execute(self.sql.set_match, {"key_match": match_id, "score": _dump(score)})

    def finish_match(
        self,
        match_id: int,
        score: list[int],
        winner: int | None,
        reason: str | None,
        status: str = "finished",
        finished_at: float | None = None,
        *,
        epoch: int | None = None,
    ) -> None:
        """Close the match record (once: a finished match stays as it was first closed)."""
        values = {
            "key_match": match_id,
            "status": status,
            "score": _dump(score),
            "winner": winner,
            "reason": reason,
            "finished_at": time.time() if finished_at is None else finished_at,
        }
        with self.transaction() as conn:
            self._fence_match(conn, match_id, epoch)
            conn.execute(self.sql.finish_match, values)

    def match(self, match_id: int) -> MatchRecord | None:
        rows = self._matches(self.sql.match, {"key_match": match_id})
        return rows[0] if rows else None

    def recent_matches(
        self, limit: int = 20, status: str | None = None, room_id: str | None = None
    ) -> list[MatchRecord]:
        """Newest first; `status` filters ("playing", "finished", "abandoned"), or
        `room_id` (the matches of one room: its first match and its rematches)."""
        if room_id is not None:
            return self._matches(self.sql.recent_room, {"key_limit": limit, "key_room": room_id})
        if status is None:
            return self._matches(self.sql.recent, {"key_limit": limit})
        return self._matches(self.sql.recent_status, {"key_limit": limit, "key_status": status})

    def _matches(self, query: Any, params: dict[str, Any]) -> list[MatchRecord]:
        with self._read() as conn:
            rows = conn.execute(query, params).all()
        return [
            MatchRecord(
                r.id,
                r.room_id,
                r.kind,
                json.loads(r.players),
                r.race_to,
                r.status,
                json.loads(r.score),
                r.winner,
                r.reason,
                r.started_at,
                r.finished_at,
                r.games,
                r.shots,
            )
            for r in rows
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
        *,
        epoch: int | None = None,
    ) -> None:
        """A finished game (frame) and the match score after it (a repeat is ignored)."""
        row = {
            "match_id": match_id,
            "n": n,
            "winner": winner,
            "reason": reason,
            "cause": cause,
            "score": _dump(score),
            "finished_at": time.time() if finished_at is None else finished_at,
        }
        with self.transaction() as conn:
            self._fence_match(conn, match_id, epoch)
            conn.execute(self.sql.add_game, row)
            self.update_score(match_id, score)

    def games(self, match_id: int) -> list[GameRecord]:
        with self._read() as conn:
            rows = conn.execute(self.sql.games, {"key_match": match_id}).all()
        return [
            GameRecord(
                r.match_id, r.n, r.winner, r.reason, r.cause, json.loads(r.score), r.finished_at
            )
            for r in rows
        ]

    # ---- shots ------------------------------------------------------------------------

    def record_shot(
        self,
        match_id: int,
        room_shot: int,
        game: int,
        seat: int,
        shot: dict[str, Any],
        table: list[float | str],
        balls: dict[str, Any],
        outcome: dict[str, Any],
        played_at: float | None = None,
        engine: str | None = None,
        motion: str | None = None,
        *,
        intended: dict[str, Any] | None = None,
        epoch: int | None = None,
    ) -> int:
        """Store a shot as number n+1 of its match; a repeat of the same room shot (played
        again after a restart or a failover) changes nothing. `engine` is the engine
        version that played it, `motion` the streamed messages (compressed here, on the
        store's thread), `intended` the stroke meant when it differs from `shot` (the
        computer's plan before its arm's error). Returns the shot's number in the match."""
        key = {"key_match": match_id, "key_shot": room_shot}
        with self.transaction() as conn:
            self._fence_match(conn, match_id, epoch)
            found = conn.scalar(self.sql.shot_n, key)
            if found is not None:
                return int(found)
            n = int(conn.scalar(self.sql.last_shot, key) or 0) + 1
            row = {
                "match_id": match_id,
                "n": n,
                "room_shot": room_shot,
                "game": game,
                "seat": seat,
                "shot": _dump(shot),
                "table_geom": _dump(table),
                "balls": _dump(balls),
                "outcome": _dump(outcome),
                "played_at": time.time() if played_at is None else played_at,
                "engine": engine,
                "motion": None
                if motion is None
                else zlib.compress(motion.encode(), MOTION_ZLIB_LEVEL),
                "intended": None if intended is None else _dump(intended),
            }
            conn.execute(self.sql.add_shot, row)
            return int(conn.execute(self.sql.shot_n, key).scalar_one())

    def shots(self, match_id: int) -> list[ShotRecord]:
        """Every shot of the match, without its motion (a list has no use for it)."""
        return self._shots(self.sql.shots, {"key_match": match_id})

    def shot(self, match_id: int, n: int) -> ShotRecord | None:
        rows = self._shots(self.sql.shot, {"key_match": match_id, "key_n": n})
        return rows[0] if rows else None

    def _shots(self, query: Any, params: dict[str, Any]) -> list[ShotRecord]:
        with self._read() as conn:
            rows = conn.execute(query, params).all()
        return [_shot_record(r) for r in rows]

    # ---- live rooms -------------------------------------------------------------------

    def save_room(self, room_id: str, snapshot_json: str, *, epoch: int | None = None) -> None:
        row = {"room_id": room_id, "snapshot": snapshot_json, "updated_at": time.time()}
        with self.transaction() as conn:
            self._fence(conn, room_id, epoch)
            conn.execute(self.sql.save_room, row)

    def delete_room(self, room_id: str, *, epoch: int | None = None) -> None:
        """Forget the saved room (its owner row stays, so a stale owner cannot bring the
        room back)."""
        with self.transaction() as conn:
            self._fence(conn, room_id, epoch)
            conn.execute(self.sql.delete_room, {"key_room": room_id})

    def rooms(self) -> list[RoomSnapshot]:
        with self._read() as conn:
            rows = conn.execute(self.sql.rooms).all()
        return [RoomSnapshot(r.room_id, json.loads(r.snapshot), r.updated_at) for r in rows]

    def room(self, room_id: str) -> RoomSnapshot | None:
        """One saved room (a process taking it over reads just that one)."""
        with self._read() as conn:
            r = conn.execute(self.sql.room, {"key_room": room_id}).first()
        return None if r is None else RoomSnapshot(r.room_id, json.loads(r.snapshot), r.updated_at)


def _shot_record(r: Row[Any]) -> ShotRecord:
    return ShotRecord(
        r.match_id,
        r.n,
        r.room_shot,
        r.game,
        r.seat,
        json.loads(r.shot),
        json.loads(r.table_geom),
        json.loads(r.balls),
        json.loads(r.outcome),
        r.played_at,
        r.engine,
        None if r.motion is None else zlib.decompress(r.motion).decode(),
        None if r.intended is None else json.loads(r.intended),
    )
