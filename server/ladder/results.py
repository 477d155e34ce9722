"""Ranked results: a ranked room (made by Play now or by two friends who agreed) is watched
until its first match ends, and that match is rated in the store."""

from __future__ import annotations

from collections.abc import Callable

from server.rooms import LiveRoom, Room, RoomRegistry

from .player_data import PlayerData, RankedRoom
from .watch import RankedWatch


class RankedResults:
    def __init__(
        self,
        registry: RoomRegistry,
        data: PlayerData,
        match_ids: Callable[[Room], int | None] | None = None,
    ) -> None:
        """`match_ids`: the history's id of a room's match (the recorder's), for the replay
        link of a ranked result."""
        self.registry = registry
        self.data = data
        self.match_ids = match_ids

    def start(self, live: LiveRoom, ranked: RankedRoom, at: float) -> None:
        """The room is ranked from now: watched here, and stored (queued) as ranked."""
        self.watch(live, ranked)
        self.data.add_ranked(ranked, at)

    def watch(self, live: LiveRoom, ranked: RankedRoom) -> None:
        """Rate the room's first match when it ends (also for a room restored after a
        restart)."""

        def over(room: Room) -> None:
            """Rated when won with at least one shot played; a match ended before any shot
            (a no-show, a concession at the table) or abandoned closes unrated, as the
            history marks it abandoned."""
            assert room.match is not None
            number = self.match_ids(room) if self.match_ids is not None else None
            played = room.shots_played > 0 and not room.abandoned
            winner = room.match.winner if played else None
            self.data.rate_ranked(ranked, number, winner, self.registry.clock.wall())

        live.observer = RankedWatch(live.observer, over)

    def restore(self, open_ranked: list[RankedRoom]) -> int:
        """After a restart or a takeover: watch again the ranked rooms the registry holds
        (those not watched yet); returns how many."""
        watched = 0
        for ranked in open_ranked:
            live = self.registry.get(ranked.room_id)
            if live is not None and not isinstance(live.observer, RankedWatch):
                self.watch(live, ranked)
                watched += 1
        return watched
