"""Drills on a practice table, each with a score the profile keeps as personal bests.

- "position" ("play this position again"): the stored table before an analysed shot
  (exact), with the ball in hand the shooter had; the par is the pro level's chance from
  there (the analysis' best choice). The first shot makes it when it pockets a ball
  without a foul: score 1, else 0.
- "ghost" (ghost 9-ball): a 9-ball rack, broken from behind the head string; every shot
  must hit the lowest ball first and pocket a ball without a foul, else the ghost wins the
  rack. The score is the balls pocketed; clearing the rack beats the ghost.

The table is set up when its one seat is taken, and kept with the room (a restart brings
the drill back).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

from server.engine import CUE, BallSet, ShotResult, rack
from server.rules import Match, Outcome
from server.rules.outcome import BEHIND_HEAD_STRING
from server.rules.shotfacts import shot_facts

DRILL_KINDS = ("position", "ghost")


@dataclass(frozen=True)
class DrillSetup:
    """Where a drill starts. position: `balls` (`BallSet.to_dict()`), the ball in hand
    area (None: play the cue ball where it lies), the pro's chance there (`par`) and the
    shot it comes from (`match_id`, `n`). ghost: none of those (a 9-ball rack from the
    room's seed)."""

    balls: dict[str, Any] | None = None
    ball_in_hand: str | None = None
    par: float | None = None
    match_id: int | None = None
    n: int | None = None
    kind: str = "position"


@dataclass(frozen=True)
class DrillScore:
    """How the drill went so far: `score` (position: 1 made, 0 missed; ghost: balls
    pocketed), `done` (no more to score), `won` (ghost: the rack cleared)."""

    score: int = 0
    done: bool = False
    won: bool = False


def set_up(match: Match, setup: DrillSetup) -> None:
    """The match's game at the drill's table: no break to play by the rules, the ball in
    hand as it was (a ghost rack: behind the head string, to break)."""
    game = match.game
    if setup.kind == "ghost":
        game.balls = rack("nine_ball", game.table, seed=match.seed)
        game.ball_in_hand = BEHIND_HEAD_STRING
    else:
        assert setup.balls is not None
        game.balls = BallSet.from_dict(setup.balls)
        game.ball_in_hand = setup.ball_in_hand
    game.breaking = False


def made(outcome: Outcome) -> bool:
    """A ball pocketed without a foul."""
    return any(b != CUE for b in outcome.pocketed) and not outcome.fouls


def scored(
    setup: DrillSetup, score: DrillScore, before: BallSet, result: ShotResult, outcome: Outcome
) -> DrillScore:
    """The drill's score after a shot from `before`."""
    if score.done:
        return score
    if setup.kind != "ghost":
        return DrillScore(int(made(outcome)), done=True)
    objects = [b for b in before.on_table_ids() if b != CUE]
    first = shot_facts(before, result).first_contact
    if not objects or first != min(objects) or not made(outcome):
        return replace(score, done=True)  # the ghost wins the rack
    potted = score.score + sum(1 for b in outcome.pocketed if b != CUE)
    cleared = not any(b != CUE for b in result.final.on_table_ids())
    return DrillScore(potted, done=cleared, won=cleared)
