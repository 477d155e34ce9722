"""Ranked tables made for friends: rated only when both players agree.

The creator agrees by opening the table ranked; each player who sits down agrees again on
their join. Once both seats are taken by agreed players the room is rated exactly like a
Play now room (`RankedResults`: its first match only). One process only: in cluster mode a
ranked table is refused. A table waiting for its second player is known in memory only (a
restart opens it again unranked); once both sit down it is stored like a Play now room.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from server.players import Player
from server.rooms import LiveRoom

from .player_data import RankedRoom
from .results import RankedResults


@dataclass
class RankedTable:
    """A ranked friends' table: who has sat down (seat -> player id, name) so far."""

    kind: str
    seated: dict[int, tuple[str, str]] = field(default_factory=dict)
    rated: bool = False  # both seats taken: its first match is being rated


class RankedTables:
    """The ranked friends' tables of this process, by room id."""

    def __init__(self, results: RankedResults) -> None:
        self.results = results
        self.tables: dict[str, RankedTable] = {}

    def is_ranked(self, room_id: str) -> bool:
        return room_id in self.tables

    def add(self, room_id: str, kind: str, live_ids: set[str]) -> None:
        for gone in [r for r in self.tables if r not in live_ids]:  # closed rooms
            del self.tables[gone]
        self.tables[room_id] = RankedTable(kind)

    def seated(self, live: LiveRoom, seat: int, player: Player) -> None:
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
        self.results.start(live, ranked, live.clock.wall())
