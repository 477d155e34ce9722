"""Ranked tables made for friends: rated only when both players agree.

The creator agrees by opening the table with `ranked: true`; each player who sits down
agrees again with `ranked: true` on their join (the join dialog says the rating will
change). A join without that agreement, or without a profile, is refused and seats nobody.
Once both seats are taken by agreed profile players the room is rated exactly like a Play
now room (`Matchmaker.watch`: its first match only). One process only: in cluster mode a
ranked table is refused. A table waiting for its second player is known in memory only (a
restart opens it again unranked); once both sit down it is stored like a Play now room.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from fastapi import HTTPException, Request

from server.cluster import Cluster
from server.players import Player, secret_hash
from server.rooms import LiveRoom

from .identity import cookie_secret
from .playerdata import PlayerData, RankedRoom
from .playnow import Matchmaker

NEEDS_AGREEMENT = {
    "code": "ranked_needs_agreement",
    "message": "This table is ranked: join with ranked true (and a profile) to agree that "
    "your rating will change.",
}


@dataclass
class RankedTable:
    """A ranked friends' table: who has sat down (seat -> player id, name) so far."""

    kind: str
    seated: dict[int, tuple[str, str]] = field(default_factory=dict)
    rated: bool = False  # both seats taken: its first match is being rated


class RankedTables:
    """The ranked friends' tables of this process, by room id."""

    def __init__(self) -> None:
        self.tables: dict[str, RankedTable] = {}

    def is_ranked(self, room_id: str) -> bool:
        return room_id in self.tables

    def add(self, room_id: str, kind: str, live_ids: set[str]) -> None:
        for gone in [r for r in self.tables if r not in live_ids]:  # closed rooms
            del self.tables[gone]
        self.tables[room_id] = RankedTable(kind)

    def seated(
        self, live: LiveRoom, seat: int, player: Player, matchmaker: Matchmaker, data: PlayerData
    ) -> None:
        """`player` sits at `seat` having agreed; with both seats agreed, rate the room (run
        in the same step of the loop as the join, before any shot can be played)."""
        table = self.tables.get(live.room.room_id)
        if table is None or table.rated:
            return
        table.seated[seat] = (player.id, player.name)
        if len(table.seated) < 2:
            return
        table.rated = True
        (first, first_name), (second, second_name) = table.seated[0], table.seated[1]
        ranked = RankedRoom(
            live.room.room_id, table.kind, (first, second), (first_name, second_name)
        )
        matchmaker.watch(live, ranked)
        data.add_ranked(ranked, live.clock.wall())


def seat_agreed(request: Request, live: LiveRoom, seat: int, player: Player) -> None:
    """An agreed player took `seat` in a ranked friends' table of this process."""
    matchmaker = request.app.state.matchmaker
    if isinstance(matchmaker, Matchmaker):  # one process (cluster mode makes none)
        tables_of(request).seated(live, seat, player, matchmaker, request.app.state.players)


def check_create(
    game: str, opponent: str | None, cluster: Cluster | None, player: Player | None
) -> None:
    """Refuse a ranked table that cannot be one (422 `bad_ranked`), one asked for without a
    profile (401 `no_player`) or in cluster mode (409 `ranked_unavailable`)."""
    if game == "practice" or opponent is not None:
        raise HTTPException(
            422,
            {
                "code": "bad_ranked",
                "message": "Only 8-ball and 9-ball between two players can be ranked.",
            },
        )
    if player is None:
        raise HTTPException(
            401, {"code": "no_player", "message": "No profile yet: load the page first."}
        )
    if cluster is not None:
        raise HTTPException(
            409,
            {"code": "ranked_unavailable", "message": "Ranked tables are made by Play now here."},
        )


async def asking_player(request: Request) -> Player | None:
    """The player of the request's cookie, if any."""
    secret = cookie_secret(request)
    if secret is None:
        return None
    data: PlayerData = request.app.state.players
    return await data.by_secret(secret_hash(secret))


def tables_of(request: Request) -> RankedTables:
    """This app's ranked friends' tables (made on first use)."""
    state = request.app.state
    tables: RankedTables | None = getattr(state, "ranked_tables", None)
    if tables is None:
        tables = state.ranked_tables = RankedTables()
    return tables
