"""Drills: a practice table set up from an analysed shot ("play this position again").

The table is the stored one before the shot (exact), with the ball in hand the shooter had;
the par is the pro level's chance from there (the analysis' best choice), so the player
knows what a good try looks like. The table is set up when its one seat is taken, and
kept with the room (a restart brings the drill back).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from server.engine import CUE, BallSet
from server.rules import Match, Outcome


@dataclass(frozen=True)
class DrillSetup:
    """Where a drill starts: `balls` (`BallSet.to_dict()`), the ball in hand area (None:
    play the cue ball where it lies), the pro's chance from there, and the shot it comes
    from (`match_id`, `n`)."""

    balls: dict[str, Any]
    ball_in_hand: str | None
    par: float
    match_id: int
    n: int


def set_up(match: Match, setup: DrillSetup) -> None:
    """The match's game at the drill's table: no break, the ball in hand as it was."""
    game = match.game
    game.balls = BallSet.from_dict(setup.balls)
    game.breaking = False
    game.ball_in_hand = setup.ball_in_hand


def made(outcome: Outcome) -> bool:
    """A drill's first shot made the position: a ball pocketed without a foul (the same
    test as `server.store.drills`, which reads it from the stored outcome)."""
    return any(b != CUE for b in outcome.pocketed) and not outcome.fouls
