"""Players' records: profiles (the secret's hash, never the secret), Glicko-2 ratings per
game kind, and ranked rooms with their result. Typed rows in, typed rows out; the rating
arithmetic is `server.players`' (the API layer runs it inside `transaction()`).
"""

from __future__ import annotations

import json
from collections.abc import Collection
from dataclasses import dataclass
from typing import Any

from sqlalchemy import Connection, Row, delete, exists, func, literal, select, union_all
from sqlalchemy.dialects import postgresql, sqlite

from server.codec import encode

from .repository import Repository
from .schema import (
    matches,
    metadata,
    player_ratings,
    player_seats,
    players,
    ranked_rooms,
    sessions,
    shots,
)


@dataclass(frozen=True)
class PlayerRecord:
    id: str
    name: str
    created_at: float
    account: bool = False  # claimed with a password or a passkey (server.accounts)


_PROFILE = (
    players.c.id,
    players.c.name,
    players.c.created_at,
    players.c.name_key.is_not(None).label("account"),
)


@dataclass(frozen=True)
class RatingRecord:
    player_id: str
    kind: str
    rating: float
    rd: float
    volatility: float
    games: int
    wins: int
    rated_at: float | None


@dataclass(frozen=True)
class RankedRecord:
    """A ranked (Play now) room: its two players in seat order and, once its first match
    ended, the result and both ratings before and after (`[rating, rd, volatility]`)."""

    room_id: str
    kind: str
    players: tuple[str, str]
    names: tuple[str, str]
    started_at: float
    match_id: int | None = None
    winner: int | None = None
    before: list[list[float]] | None = None
    after: list[list[float]] | None = None
    finished_at: float | None = None


@dataclass(frozen=True)
class PlayerMatch:
    """A match played in a seat the player took (any room: friends', Play now, the
    computer's)."""

    match_id: int
    room_id: str
    kind: str
    players: list[str]
    seat: int
    status: str  # playing | finished | abandoned
    score: list[int]
    winner: int | None
    started_at: float
    finished_at: float | None
    shots: int


class PlayerRows:
    """Queries over the repository's connection (each method one transaction, or part of
    an enclosing `repo.transaction()`)."""

    def __init__(self, repo: Repository) -> None:
        self.repo = repo

    # ---- profiles ---------------------------------------------------------------------

    def add_player(self, player_id: str, name: str, secret_hash: str, created_at: float) -> None:
        with self.repo.transaction() as conn:
            conn.execute(
                players.insert().values(
                    id=player_id, name=name, secret_hash=secret_hash, created_at=created_at
                )
            )

    def player_by_secret(self, secret_hash: str) -> PlayerRecord | None:
        """The player of a guest's cookie, or of an account's session (its expiry is
        `server.accounts`' to check before)."""
        by_guest = select(*_PROFILE).where(players.c.secret_hash == secret_hash)
        by_session = (
            select(*_PROFILE)
            .join(sessions, sessions.c.player_id == players.c.id)
            .where(sessions.c.id_hash == secret_hash)
        )
        with self.repo.transaction(write=False) as conn:
            row = conn.execute(union_all(by_guest, by_session)).first()
        return None if row is None else PlayerRecord(*row)

    def player(self, player_id: str) -> PlayerRecord | None:
        with self.repo.transaction(write=False) as conn:
            row = conn.execute(select(*_PROFILE).where(players.c.id == player_id)).first()
        return None if row is None else PlayerRecord(*row)

    def rename_player(self, player_id: str, name: str) -> None:
        with self.repo.transaction() as conn:
            conn.execute(players.update().where(players.c.id == player_id).values(name=name))

    # ---- ratings ----------------------------------------------------------------------

    def ratings(self, player_id: str) -> list[RatingRecord]:
        with self.repo.transaction(write=False) as conn:
            rows = conn.execute(
                select(player_ratings).where(player_ratings.c.player_id == player_id)
            ).all()
        return [_rating(r) for r in rows]

    def rating(self, player_id: str, kind: str) -> RatingRecord | None:
        with self.repo.transaction(write=False) as conn:
            return self._rating(conn, player_id, kind)

    def _rating(self, conn: Connection, player_id: str, kind: str) -> RatingRecord | None:
        row = conn.execute(
            select(player_ratings).where(
                player_ratings.c.player_id == player_id, player_ratings.c.kind == kind
            )
        ).first()
        return None if row is None else _rating(row)

    def save_rating(self, record: RatingRecord) -> None:
        values = {
            "rating": record.rating,
            "rd": record.rd,
            "volatility": record.volatility,
            "games": record.games,
            "wins": record.wins,
            "rated_at": record.rated_at,
        }
        insert = _insert(self.repo.dialect)(player_ratings)
        with self.repo.transaction() as conn:
            conn.execute(
                insert.values(
                    player_id=record.player_id, kind=record.kind, **values
                ).on_conflict_do_update(index_elements=["player_id", "kind"], set_=values)
            )

    def rated(self, kind: str) -> list[tuple[RatingRecord, str]]:
        """Every rated player of `kind` with their name (for the leaderboard)."""
        with self.repo.transaction(write=False) as conn:
            rows = conn.execute(
                select(player_ratings, players.c.name)
                .join(players, players.c.id == player_ratings.c.player_id)
                .where(player_ratings.c.kind == kind, player_ratings.c.games > 0)
            ).all()
        return [(_rating(r), r.name) for r in rows]

    def prune_guests(self, created_before: float, keep: Collection[str], limit: int) -> int:
        """Delete up to `limit` guests made before `created_before` that never played: not
        an account, and no row anywhere refers to them (no seat taken, no rating, no ranked
        room, no session: every table with a key to `players`); never one of `keep`
        (waiting for Play now). How many were deleted. The one place that decides who is
        pruned."""
        pid = players.c.id
        doomed = select(pid).where(
            players.c.created_at < created_before,
            players.c.name_key.is_(None),  # an account is never pruned
        )
        for table in metadata.sorted_tables:
            for key in table.foreign_keys:
                if key.column is pid:
                    doomed = doomed.where(~exists().where(key.parent == pid))
        if keep:
            doomed = doomed.where(pid.not_in(list(keep)))
        with self.repo.transaction() as conn:
            result = conn.execute(delete(players).where(pid.in_(doomed.limit(limit))))
        return int(result.rowcount)

    # ---- seats ------------------------------------------------------------------------

    def add_seat(self, secret_hash: str, room_id: str, seat: int, joined_at: float) -> None:
        """The player of `secret_hash` (a guest's cookie or an account's session, if any)
        sat in `room_id`'s `seat` (once a room)."""
        values = (literal(room_id), literal(seat), literal(joined_at))
        found = union_all(
            select(players.c.id, *values).where(players.c.secret_hash == secret_hash),
            select(sessions.c.player_id, *values).where(sessions.c.id_hash == secret_hash),
        )
        query = _insert(self.repo.dialect)(player_seats).from_select(
            ["player_id", "room_id", "seat", "joined_at"], found
        )
        with self.repo.transaction() as conn:
            conn.execute(query.on_conflict_do_nothing(index_elements=["player_id", "room_id"]))

    def add_player_seat(self, player_id: str, room_id: str, seat: int, joined_at: float) -> None:
        with self.repo.transaction() as conn:
            conn.execute(
                _insert(self.repo.dialect)(player_seats)
                .values(player_id=player_id, room_id=room_id, seat=seat, joined_at=joined_at)
                .on_conflict_do_nothing(index_elements=["player_id", "room_id"])
            )

    def matches_of(self, player_id: str, limit: int) -> list[PlayerMatch]:
        """The matches played in the player's seats, newest first."""
        shot_count = (
            select(func.count()).select_from(shots).where(shots.c.match_id == matches.c.id)
        ).scalar_subquery()
        query = (
            select(
                matches.c.id,
                matches.c.room_id,
                matches.c.kind,
                matches.c.players,
                player_seats.c.seat,
                matches.c.status,
                matches.c.score,
                matches.c.winner,
                matches.c.started_at,
                matches.c.finished_at,
                shot_count.label("shots"),
            )
            .join(player_seats, player_seats.c.room_id == matches.c.room_id)
            .where(player_seats.c.player_id == player_id)
            .order_by(matches.c.started_at.desc(), matches.c.id.desc())
            .limit(limit)
        )
        with self.repo.transaction(write=False) as conn:
            rows = conn.execute(query).all()
        return [
            PlayerMatch(
                r.id,
                r.room_id,
                r.kind,
                json.loads(r.players),
                r.seat,
                r.status,
                json.loads(r.score),
                r.winner,
                r.started_at,
                r.finished_at,
                r.shots,
            )
            for r in rows
        ]

    # ---- ranked rooms -----------------------------------------------------------------

    def add_ranked(self, record: RankedRecord) -> None:
        with self.repo.transaction() as conn:
            conn.execute(
                _insert(self.repo.dialect)(ranked_rooms)
                .values(
                    room_id=record.room_id,
                    kind=record.kind,
                    player0=record.players[0],
                    player1=record.players[1],
                    names=encode(list(record.names)),
                    started_at=record.started_at,
                )
                .on_conflict_do_nothing(index_elements=["room_id"])
            )

    def ranked(self, room_id: str) -> RankedRecord | None:
        with self.repo.transaction(write=False) as conn:
            row = conn.execute(
                select(ranked_rooms).where(ranked_rooms.c.room_id == room_id)
            ).first()
        return None if row is None else _ranked(row)

    def open_ranked(self, room_ids: list[str] | None = None) -> list[RankedRecord]:
        """Ranked rooms without a result yet (of `room_ids` only, when given)."""
        query = select(ranked_rooms).where(ranked_rooms.c.finished_at.is_(None))
        if room_ids is not None:
            query = query.where(ranked_rooms.c.room_id.in_(room_ids))
        with self.repo.transaction(write=False) as conn:
            rows = conn.execute(query).all()
        return [_ranked(r) for r in rows]

    def finish_ranked(self, record: RankedRecord) -> bool:
        """Store the result of a ranked room, once: False (and nothing changed) if it was
        already stored."""
        assert record.finished_at is not None
        with self.repo.transaction() as conn:
            done = conn.execute(
                ranked_rooms.update()
                .where(
                    ranked_rooms.c.room_id == record.room_id, ranked_rooms.c.finished_at.is_(None)
                )
                .values(
                    match_id=record.match_id,
                    winner=record.winner,
                    before=encode(record.before),
                    after=encode(record.after),
                    finished_at=record.finished_at,
                )
            )
        return bool(done.rowcount)

    def ranked_of(self, player_id: str, limit: int) -> list[RankedRecord]:
        """The player's rated ranked rooms, newest first."""
        with self.repo.transaction(write=False) as conn:
            rows = conn.execute(
                select(ranked_rooms)
                .where(
                    (ranked_rooms.c.player0 == player_id) | (ranked_rooms.c.player1 == player_id),
                    ranked_rooms.c.winner.is_not(None),
                )
                .order_by(ranked_rooms.c.finished_at.desc(), ranked_rooms.c.room_id)
                .limit(limit)
            ).all()
        return [_ranked(r) for r in rows]


def _insert(dialect: str) -> Any:
    return postgresql.insert if dialect == "postgresql" else sqlite.insert


def _rating(row: Row[Any]) -> RatingRecord:
    return RatingRecord(
        row.player_id,
        row.kind,
        row.rating,
        row.rd,
        row.volatility,
        row.games,
        row.wins,
        row.rated_at,
    )


def _ranked(row: Row[Any]) -> RankedRecord:
    names = json.loads(row.names)
    return RankedRecord(
        row.room_id,
        row.kind,
        (row.player0, row.player1),
        (names[0], names[1]),
        row.started_at,
        row.match_id,
        row.winner,
        None if row.before is None else json.loads(row.before),
        None if row.after is None else json.loads(row.after),
        row.finished_at,
    )
