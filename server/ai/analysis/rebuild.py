"""The game as it stood before each stored shot, rebuilt from the stored rows.

A stored shot keeps the table before it (exact), the seat, the stroke and the judged
outcome, but not the rest of the game's state (8-ball groups, fouls in a row, a pending
break, a push out): those are rebuilt by playing the stored strokes forward through the
rules, with the table reset to the stored one before every shot (so a placed cue ball, a
re-rack or an engine change since cannot lead the rebuilt game astray).
"""

from __future__ import annotations

import contextlib
import copy
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

from server.codec import from_data
from server.engine import BallSet, Shot, Table, simulate
from server.rules import Game
from server.rules.errors import IllegalActionError
from server.rules.shotfacts import shot_facts

EIGHT = 8


@dataclass(frozen=True)
class StoredShot:
    """One shot as the history keeps it (`server.store.ShotRecord`'s fields the analysis
    reads): the table before it, the stroke as sent, and what the rules made of it."""

    n: int
    game: int  # the game (frame) of the match it was played in, from 1
    seat: int
    shot: dict[str, Any]  # {"angle", "speed", "tip": [side, height]}
    table: list[float | str]  # Table.from_fields(table): a snooker table ends with its style
    balls: dict[str, Any]  # BallSet.to_dict() before the shot
    outcome: dict[str, Any]  # Outcome.to_dict()
    # The stroke the player meant, when it differs from the one played (a computer's
    # plan before its arm's error); None: `shot` is what they meant (a person's, as sent).
    intended: dict[str, Any] | None = None


@dataclass(frozen=True)
class Before:
    """The game just before a stored shot (a copy: nothing else holds it), the stroke
    meant (what the analysis judges), and the pocket it was called in (None: no call was
    needed)."""

    stored: StoredShot
    game: Game
    stroke: Shot
    call: int | None
    push_out: bool  # 9-ball: the shot was a declared push out


def positions(kind: str, players: list[str], shots: list[StoredShot]) -> Iterator[Before]:
    """The game before each of `shots` (in match order), played forward through the rules."""
    game: Game | None = None
    game_no = -1
    for stored in shots:
        table = from_data(Table, stored.table)
        if game is None or stored.game != game_no or game.over:
            game = Game.new(kind, players, breaker=stored.seat, table=table)
            game_no = stored.game
        elif game.decision is not None:
            _decide(game, stored.seat)
        game.balls = BallSet.from_dict(stored.balls)
        game.turn = stored.seat
        played = from_data(Shot, stored.shot)
        stroke = played if stored.intended is None else from_data(Shot, stored.intended)
        result = simulate(game.table, game.balls, played)
        decision = stored.outcome.get("decision") or {}
        game.push_out_declared = "pass" in decision.get("options", ())
        call = None
        if game.requires_call:  # where the stroke meant drops the 8, else where it dropped
            meant = result if stroke is played else simulate(game.table, game.balls, stroke)
            call = _call(game, meant, result)
        game.called_pocket = call
        yield Before(stored, copy.deepcopy(game), stroke, call, game.push_out_declared)
        with contextlib.suppress(IllegalActionError):  # the stored outcome says what followed
            game.apply(stored.seat, result)
        _follow(game, stored.outcome)


def _call(game: Game, *results: Any) -> int:
    """The pocket the 8 was called in (the stored rows keep no call): where it dropped in
    the first of `results` that drops it, else its nearest pocket."""
    for result in results:
        facts = shot_facts(game.balls, result)
        if EIGHT in facts.pockets:
            return int(facts.pockets[EIGHT])
    centres = [p.center for p in game.table.pockets]
    x, y = game.balls.position_of(EIGHT)
    return min(
        range(len(centres)), key=lambda i: (centres[i][0] - x) ** 2 + (centres[i][1] - y) ** 2
    )


def _follow(game: Game, outcome: dict[str, Any]) -> None:
    """Trust the stored outcome for who plays next and from where."""
    if outcome.get("decision") is None and game.decision is not None:
        game.decision, game.pending = None, None
    if game.decision is None:
        game.turn = int(outcome["next_turn"])
        game.ball_in_hand = outcome.get("ball_in_hand")
    if outcome.get("frame_over"):
        game.over = True


def _decide(game: Game, seat: int) -> None:
    """Take the pending decision the way that hands the next shot to `seat` (the stored
    rows keep the shots, not the decisions between them)."""
    assert game.decision is not None
    chooser = game.decision.seat
    for option in game.decision.options:
        trial = copy.deepcopy(game)
        trial.decide(chooser, option)
        if trial.turn == seat and trial.decision is None:
            game.decide(chooser, option)
            return
    game.decide(chooser, game.decision.options[0])
