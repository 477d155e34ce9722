"""The players' records as the ladder needs them: the store's rows turned into
`server.players` values, and the rating of a ranked match computed inside the store's own
transaction (read both ratings, rate, write both and the result, or nothing), so two
results can never be rated from the same stale rating.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, replace

from server.players import KindRating, Player, Rating, rate_ranked
from server.store import Database
from server.store.analyses import AnalysisRows
from server.store.drills import DrillRows, DrillTry
from server.store.players import (
    PlayerMatch,
    PlayerRecord,
    PlayerRows,
    RankedRecord,
    RatingRecord,
)


@dataclass(frozen=True)
class RankedRoom:
    room_id: str
    kind: str
    players: tuple[str, str]  # ids, seat order
    names: tuple[str, str]


def _player(record: PlayerRecord) -> Player:
    return Player(record.id, record.name, record.created_at, bool(record.account))


def _kind_rating(record: RatingRecord) -> KindRating:
    return KindRating(
        record.player_id,
        record.kind,
        Rating(record.rating, record.rd, record.volatility),
        record.games,
        record.wins,
        record.rated_at,
    )


def _record(rating: KindRating) -> RatingRecord:
    r = rating.rating
    return RatingRecord(
        rating.player_id,
        rating.kind,
        r.rating,
        r.rd,
        r.volatility,
        rating.games,
        rating.wins,
        rating.rated_at,
    )


def _triple(r: Rating) -> list[float]:
    return [r.rating, r.rd, r.volatility]


class PlayerData:
    def __init__(self, db: Database) -> None:
        self.db = db

    async def add(self, player: Player, secret_hash: str) -> None:
        await self.db.call(
            lambda repo: PlayerRows(repo).add_player(
                player.id, player.name, secret_hash, player.created_at
            )
        )

    async def by_secret(self, secret_hash: str) -> Player | None:
        found = await self.db.call(lambda repo: PlayerRows(repo).player_by_secret(secret_hash))
        return None if found is None else _player(found)

    async def get(self, player_id: str) -> Player | None:
        found = await self.db.call(lambda repo: PlayerRows(repo).player(player_id))
        return None if found is None else _player(found)

    async def prune_guests(self, created_before: float, keep: set[str], limit: int) -> int:
        """Delete up to `limit` guests made before `created_before` that never played
        (`PlayerRows.prune_guests`); how many were."""
        return await self.db.call(
            lambda repo: PlayerRows(repo).prune_guests(created_before, keep, limit)
        )

    async def rename(self, player_id: str, name: str) -> None:
        await self.db.call(lambda repo: PlayerRows(repo).rename_player(player_id, name))

    async def ratings(self, player_id: str, kinds: tuple[str, ...]) -> dict[str, KindRating]:
        """The player's rating in each of `kinds` (a new rating where never rated)."""
        rows = await self.db.call(lambda repo: PlayerRows(repo).ratings(player_id))
        found = {r.kind: _kind_rating(r) for r in rows}
        return {kind: found.get(kind, KindRating(player_id, kind)) for kind in kinds}

    async def rated(self, kind: str) -> list[tuple[KindRating, str]]:
        rows = await self.db.call(lambda repo: PlayerRows(repo).rated(kind))
        return [(_kind_rating(r), name) for r, name in rows]

    async def recent(self, player_id: str, limit: int) -> list[RankedRecord]:
        return await self.db.call(lambda repo: PlayerRows(repo).ranked_of(player_id, limit))

    async def matches(self, player_id: str, limit: int) -> list[PlayerMatch]:
        return await self.db.call(lambda repo: PlayerRows(repo).matches_of(player_id, limit))

    async def accuracies(self, seats: dict[int, int]) -> dict[int, float]:
        """The player's accuracy in each analysed match of `seats` (match id -> their
        seat), from the stored analyses; a match not analysed (yet) is left out."""
        results = await self.db.call(lambda repo: AnalysisRows(repo).results(list(seats)))
        found = {}
        for match_id, text in results.items():
            players = json.loads(text).get("players", [])
            seat = seats[match_id]
            if seat < len(players) and players[seat].get("accuracy") is not None:
                found[match_id] = float(players[seat]["accuracy"])
        return found

    async def drills(self, player_id: str) -> list[DrillTry]:
        """The drills the player set up ("play this position again"), oldest first."""
        return await self.db.call(lambda repo: DrillRows(repo).tries_of(player_id))

    def seated(self, secret_hash: str, room_id: str, seat: int, at: float) -> None:
        """Queued: the player of this secret (if any) took `seat` in `room_id`."""
        self.db.write(
            lambda repo: PlayerRows(repo).add_seat(secret_hash, room_id, seat, at), "add seat"
        )

    def player_seated(self, player_id: str, room_id: str, seat: int, at: float) -> None:
        self.db.write(
            lambda repo: PlayerRows(repo).add_player_seat(player_id, room_id, seat, at),
            "add seat",
        )

    async def open_ranked(self, room_ids: list[str] | None = None) -> list[RankedRoom]:
        rows = await self.db.call(lambda repo: PlayerRows(repo).open_ranked(room_ids))
        return [RankedRoom(r.room_id, r.kind, r.players, r.names) for r in rows]

    def add_ranked(self, room: RankedRoom, at: float) -> None:
        """Queued (the event loop does not wait): the room is ranked from now."""
        record = RankedRecord(room.room_id, room.kind, room.players, room.names, at)
        self.db.write(lambda repo: PlayerRows(repo).add_ranked(record), "add ranked room")

    def rate_ranked(
        self, room: RankedRoom, match_id: int | None, winner: int | None, at: float
    ) -> None:
        """Queued: rate both players of a ranked room's match won by seat `winner` (None:
        the match closes unrated)."""
        self.db.write(
            lambda repo: rate_in_store(PlayerRows(repo), room, match_id, winner, at),
            "rate ranked match",
        )


def _stored_rating(rows: PlayerRows, player_id: str, kind: str) -> KindRating:
    found = rows.rating(player_id, kind)
    return KindRating(player_id, kind) if found is None else _kind_rating(found)


def rate_in_store(
    rows: PlayerRows, room: RankedRoom, match_id: int | None, winner: int | None, at: float
) -> bool:
    """One transaction: both ratings as stored, rated by the result, written with the
    result; False (nothing written) when this room's result was stored already. Without a
    `winner` the room is closed unrated. Rated by `rate_ranked` (the farm rule)."""
    with rows.repo.transaction():
        found = rows.ranked(room.room_id)
        if found is None or found.finished_at is not None:
            return False
        unrated = RankedRecord(
            room.room_id,
            room.kind,
            room.players,
            room.names,
            found.started_at,
            match_id,
            finished_at=at,
        )
        if winner is None:
            rows.finish_ranked(unrated)
            return True
        a, b = (_stored_rating(rows, p, room.kind) for p in room.players)
        new_a, new_b = rate_ranked(a, b, winner == 0, at)
        rated = replace(
            unrated,
            winner=winner,
            before=[_triple(a.at(at)), _triple(b.at(at))],
            after=[_triple(new_a.rating), _triple(new_b.rating)],
        )
        rows.finish_ranked(rated)
        rows.save_rating(_record(new_a))
        rows.save_rating(_record(new_b))
    return True
