"""Drills' practice rooms (`server.rooms.drills`): which room is which drill, and how it
went (kept by the room's recorder after every shot), for the personal bests on the
profile."""

from __future__ import annotations

from dataclasses import dataclass

from sqlalchemy import select

from .repository import Repository
from .schema import drills, player_seats


@dataclass(frozen=True)
class DrillTry:
    room_id: str
    kind: str  # position | ghost | lineup
    match_id: int | None
    n: int | None
    par: float | None
    created_at: float
    score: int | None  # None: not played yet; ghost, lineup: the best try's balls
    done: bool
    won: bool
    tries: int = 1  # ghost, lineup: tries played in the room
    cleared: int = 0  # of them, won


class DrillRows:
    def __init__(self, repo: Repository) -> None:
        self.repo = repo

    def add(
        self,
        room_id: str,
        kind: str,
        now: float,
        match_id: int | None = None,
        n: int | None = None,
        par: float | None = None,
    ) -> None:
        row = {"room_id": room_id, "kind": kind, "match_id": match_id, "n": n, "par": par}
        with self.repo.transaction() as conn:
            conn.execute(drills.insert().values(**row, created_at=now))

    def set_score(
        self, room_id: str, score: int, done: bool, won: bool, tries: int = 1, cleared: int = 0
    ) -> None:
        """How the drill in `room_id` went so far (a room that is no drill changes nothing):
        its best try's `score`, whether the try now is `done`, whether any was `won`, the
        `tries` played and how many were won (`cleared`)."""
        with self.repo.transaction() as conn:
            conn.execute(
                drills.update()
                .where(drills.c.room_id == room_id)
                .values(score=score, done=done, won=won, tries=tries, cleared=cleared)
            )

    def tries_of(self, player_id: str) -> list[DrillTry]:
        """The drills in the seats the player took, oldest first."""
        seats = select(player_seats.c.room_id).where(player_seats.c.player_id == player_id)
        query = select(drills).where(drills.c.room_id.in_(seats)).order_by(drills.c.created_at)
        with self.repo.transaction(write=False) as conn:
            rows = conn.execute(query).all()
        return [
            DrillTry(
                r.room_id,
                r.kind,
                r.match_id,
                r.n,
                r.par,
                r.created_at,
                r.score,
                bool(r.done),
                bool(r.won),
                1 if r.tries is None else r.tries,
                int(bool(r.won)) if r.cleared is None else r.cleared,
            )
            for r in rows
        ]
