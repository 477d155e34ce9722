"""Stored matches for the analysis tests: a fixed game between two club players, the
pro's own choice and a stroke away from every ball put in place of its shots, and the
rows written to a store as a room would write them."""

from __future__ import annotations

import dataclasses
import math
from functools import cache

from server.ai import Bot
from server.ai.analysis import LEVEL, StoredShot, positions, shot_seed
from server.ai.analysis.selfplay import self_play
from server.codec import to_data
from server.engine import CUE, BallSet, Shot, Table, simulate
from server.rules.shotfacts import shot_facts
from server.store import Repository

PLAYERS = ["Ana", "Ben"]
KIND = "eight_ball"


@cache
def club_game() -> tuple[StoredShot, ...]:
    """The first six shots of a fixed game of 8-ball between two club players."""
    return tuple(self_play(KIND, ("club", "club"), seed=5)[:6])


def with_stroke(stored: StoredShot, stroke: Shot, balls: BallSet) -> StoredShot:
    return dataclasses.replace(stored, shot=to_data(stroke), balls=balls.to_dict())


def pros_choice(match_id: int, shots: list[StoredShot], n: int) -> StoredShot:
    """Shot `n` played as the pro plans it in the analysis of match `match_id`."""
    before = list(positions(KIND, PLAYERS, shots))[n - 1]
    turn = Bot(LEVEL, seed=shot_seed(match_id, n)).plan(before.game, before.stored.seat)
    assert turn.shot is not None
    balls = before.game.balls
    if turn.place is not None:
        balls = balls.with_ball(CUE, turn.place)
    return with_stroke(shots[n - 1], turn.shot, balls)


def away_from_every_ball(shots: list[StoredShot], n: int) -> StoredShot:
    """Shot `n` played firmly in a direction whose cue ball touches no other ball."""
    before = list(positions(KIND, PLAYERS, shots))[n - 1]
    table, balls = before.game.table, before.game.balls
    for k in range(72):
        shot = Shot(2 * math.pi * k / 72, 1.5)
        if shot_facts(balls, simulate(table, balls, shot)).first_contact is None:
            return with_stroke(shots[n - 1], shot, balls)
    raise AssertionError("every direction hits a ball")


def store_match(repo: Repository, match_id: int, shots: list[StoredShot], table: Table) -> None:
    """The match and its shots as a room records them, finished."""
    repo.start_match(match_id, f"room-{match_id}", KIND, PLAYERS, 1, started_at=1000.0)
    for s in shots:
        repo.record_shot(
            match_id, s.n, s.game, s.seat, s.shot, table.fields(), s.balls, s.outcome, 1000.0 + s.n
        )
    repo.finish_match(match_id, [1, 0], 0, "Ana wins.", finished_at=2000.0)
