"""Drills on a practice table, each with a score the profile keeps as personal bests.

- "position" ("play this position again"): the stored table before an analysed shot
  (exact), with the ball in hand the shooter had; the par is the pro level's chance from
  there (the analysis' best choice). The first shot makes it when it pockets a ball
  without a foul: score 1, else 0.
- "ghost" (ghost 9-ball): a 9-ball rack, broken from behind the head string; every shot
  must hit the lowest ball first and pocket a ball without a foul, else the ghost wins the
  rack. The score is the balls pocketed; clearing the rack beats the ghost.
- "lineup" (the progressive line-up): `LINEUP_FIRST` balls in a line on the long string,
  cleared in any order, the cue ball in hand at the start of each rack and played where it
  lies after; each rack cleared brings the next with one ball more (up to `LINEUP_LAST`:
  clearing that one wins); a shot that pockets no ball, or the cue ball, ends the run.
  The score is the balls pocketed in the run.

Rerack on a ghost or line-up table starts another try (a new rack, a new run); the room
keeps its tries, its best and how many were won (`DrillTries`). The table is set up when its one
seat is taken, and kept with the room (a restart brings the drill back).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

from server.engine import CUE, BallSet, ShotResult, Table, rack
from server.rules import Match, Outcome
from server.rules.game import RERACK_SEED_STEP
from server.rules.outcome import ANYWHERE, BEHIND_HEAD_STRING
from server.rules.shotfacts import shot_facts

DRILL_KINDS = ("position", "ghost", "lineup")
RACKED = ("ghost", "lineup")  # the drills Rerack starts again
LINEUP_FIRST = 3  # balls in a line-up run's first rack
LINEUP_LAST = 15  # balls in its last: clearing it wins the run
LINEUP_SPAN = (0.2, 0.8)  # the line's ends, as shares of the table's length


@dataclass(frozen=True)
class DrillSetup:
    """Where a drill starts. position: `balls` (`BallSet.to_dict()`), the ball in hand
    area (None: play the cue ball where it lies), the pro's chance there (`par`) and the
    shot it comes from (`match_id`, `n`). ghost, lineup: none of those (a 9-ball rack from
    the room's seed; balls in a line)."""

    balls: dict[str, Any] | None = None
    ball_in_hand: str | None = None
    par: float | None = None
    match_id: int | None = None
    n: int | None = None
    kind: str = "position"


@dataclass(frozen=True)
class DrillScore:
    """How the try being played went so far: `score` (position: 1 made, 0 missed; ghost,
    lineup: balls pocketed), `done` (no more to score), `won` (the ghost's rack or the
    line-up's last rack cleared), `racks` (lineup: racks cleared in this run)."""

    score: int = 0
    done: bool = False
    won: bool = False
    racks: int = 0

    @property
    def played(self) -> bool:
        """A shot was played in this try (each one pockets a ball or ends it)."""
        return self.score > 0 or self.done

    def lineup_balls(self) -> int:
        """The balls in the line-up's rack now."""
        return LINEUP_FIRST + self.racks


@dataclass(frozen=True)
class DrillTries:
    """A drill room's tries (Rerack starts another ghost rack or line-up run): how many
    were started and played, the most balls pocketed in one, and how many were won."""

    tries: int = 1
    best: int = 0
    cleared: int = 0

    def after(self, was: DrillScore, now: DrillScore) -> DrillTries:
        """Counted after a shot took the try from `was` to `now`."""
        won = now.won and not was.won
        return replace(self, best=max(self.best, now.score), cleared=self.cleared + int(won))

    def next(self, current: DrillScore) -> DrillTries:
        """Another try begins (one never played is not counted twice)."""
        return replace(self, tries=self.tries + int(current.played))


def lineup_rack(table: Table, balls: int) -> BallSet:
    """Balls 1..`balls` evenly along the long string's middle, the cue ball off it."""
    start, end = (share * table.length for share in LINEUP_SPAN)
    step = (end - start) / balls
    y = table.width / 2
    placement = {b: (start + step * (b - 0.5), y) for b in range(1, balls + 1)}
    return BallSet.place({CUE: (table.head_string / 2, table.width / 4), **placement})


def set_up(match: Match, setup: DrillSetup, racks: int = 0) -> None:
    """The match's game at the drill's table: no break to play by the rules, the ball in
    hand as it was (a ghost rack: behind the head string, to break, each rack of the game
    from its own seed; a line-up of `LINEUP_FIRST + racks` balls: anywhere)."""
    game = match.game
    if setup.kind == "ghost":
        seed = match.seed + RERACK_SEED_STEP * max(0, game.racks - 1)
        game.balls = rack("nine_ball", game.table, seed=seed)
        game.ball_in_hand = BEHIND_HEAD_STRING
    elif setup.kind == "lineup":
        game.balls = lineup_rack(game.table, LINEUP_FIRST + racks)
        game.ball_in_hand = ANYWHERE
    else:
        assert setup.balls is not None
        game.balls = BallSet.from_dict(setup.balls)
        game.ball_in_hand = setup.ball_in_hand
    game.breaking = False


def after_shot(match: Match, setup: DrillSetup, score: DrillScore) -> None:
    """The table once a drill shot is scored: a line-up run going on plays the cue ball
    where it lies, or, its rack cleared, lays out the next with the ball in hand."""
    if setup.kind != "lineup" or score.done:
        return
    game = match.game
    if any(b != CUE for b in game.balls.on_table_ids()):
        game.ball_in_hand = None
    else:
        set_up(match, setup, score.racks)


def made(outcome: Outcome) -> bool:
    """A ball pocketed without a foul."""
    return any(b != CUE for b in outcome.pocketed) and not outcome.fouls


def scored(
    setup: DrillSetup, score: DrillScore, before: BallSet, result: ShotResult, outcome: Outcome
) -> DrillScore:
    """The drill's score after a shot from `before`."""
    if score.done:
        return score
    if setup.kind == "ghost":
        return _ghost(score, before, result, outcome)
    if setup.kind == "lineup":
        return _lineup(score, result, outcome)
    return DrillScore(int(made(outcome)), done=True)


def _ghost(score: DrillScore, before: BallSet, result: ShotResult, outcome: Outcome) -> DrillScore:
    objects = [b for b in before.on_table_ids() if b != CUE]
    first = shot_facts(before, result).first_contact
    if not objects or first != min(objects) or not made(outcome):
        return replace(score, done=True)  # the ghost wins the rack
    potted = score.score + sum(1 for b in outcome.pocketed if b != CUE)
    cleared = not any(b != CUE for b in result.final.on_table_ids())
    return replace(score, score=potted, done=cleared, won=cleared)


def _lineup(score: DrillScore, result: ShotResult, outcome: Outcome) -> DrillScore:
    if not made(outcome) or CUE in outcome.pocketed:
        return replace(score, done=True)  # a miss (or the cue ball in) ends the run
    potted = score.score + sum(1 for b in outcome.pocketed if b != CUE)
    if any(b != CUE for b in result.final.on_table_ids()):
        return replace(score, score=potted)
    last = score.lineup_balls() >= LINEUP_LAST
    return replace(score, score=potted, racks=score.racks + 1, done=last, won=last)
