"""Drills set up from analysed shots: which practice room replays which stored position,
and how each try went (the first shot of the room's match: a ball pocketed without a
foul is a position made), for the personal bests on the profile."""

from __future__ import annotations

import json
from dataclasses import dataclass

from sqlalchemy import select

from .repository import Repository
from .schema import drills, matches, player_seats, shots

CUE = 0


@dataclass(frozen=True)
class DrillTry:
    room_id: str
    match_id: int  # the analysed match the position comes from
    n: int
    par: float
    created_at: float
    made: bool | None  # None: not played yet


class DrillRows:
    def __init__(self, repo: Repository) -> None:
        self.repo = repo

    def add(self, room_id: str, match_id: int, n: int, par: float, now: float) -> None:
        row = {"room_id": room_id, "match_id": match_id, "n": n, "par": par, "created_at": now}
        with self.repo.transaction() as conn:
            conn.execute(drills.insert().values(**row))

    def tries_of(self, player_id: str) -> list[DrillTry]:
        """The drills in the seats the player took, oldest first."""
        query = select(player_seats.c.room_id).where(player_seats.c.player_id == player_id)
        with self.repo.transaction(write=False) as conn:
            room_ids = list(conn.scalars(query))
        return self.tries(room_ids)

    def tries(self, room_ids: list[str]) -> list[DrillTry]:
        """The drills among `room_ids`, oldest first, each with its first shot's result."""
        if not room_ids:
            return []
        first = (
            select(matches.c.room_id, shots.c.outcome)
            .join(shots, shots.c.match_id == matches.c.id)
            .where(matches.c.room_id.in_(room_ids), shots.c.n == 1)
            .order_by(matches.c.id.desc())
        )
        query = select(drills).where(drills.c.room_id.in_(room_ids)).order_by(drills.c.created_at)
        with self.repo.transaction(write=False) as conn:
            outcomes = {r.room_id: r.outcome for r in conn.execute(first)}
            rows = conn.execute(query).all()
        return [
            DrillTry(
                r.room_id, r.match_id, r.n, r.par, r.created_at, _made(outcomes.get(r.room_id))
            )
            for r in rows
        ]


def _made(outcome: str | None) -> bool | None:
    """A ball pocketed without a foul."""
    if outcome is None:
        return None
    data = json.loads(outcome)
    return bool([b for b in data.get("pocketed", []) if b != CUE]) and not data.get("fouls")
