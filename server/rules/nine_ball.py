"""9-ball, WPA World Standardized Rules, judged from a shot's facts.

The lowest-numbered ball must be hit first; any ball pocketed on a legal shot counts; the 9
pocketed legally wins, on the break or in a combination; an illegally pocketed 9 is
re-spotted; three fouls in a row lose.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from server.engine import BallSet

from . import fouls
from .outcome import ANYWHERE, Decision
from .ruling import Ruling
from .shotfacts import ShotFacts
from .words import ball

if TYPE_CHECKING:
    from .game import Game

NINE = 9
FOULS_TO_LOSE = 3
PUSH_OUT_OPTIONS = ("shoot", "pass")


def lowest_ball(balls: BallSet) -> int | None:
    on = [b for b in balls.on_table_ids() if b != 0]
    return min(on) if on else None


def judge(game: Game, seat: int, facts: ShotFacts) -> Ruling:
    if game.push_out_declared:
        r = judge_push_out(game, seat, facts)
    else:
        r = judge_shot(game, seat, facts)
    if r.fouls and game.fouls_in_row[seat] + 1 >= FOULS_TO_LOSE:
        name = game.players[seat]
        r.winner, r.reason = 1 - seat, f"{name} fouled three times in a row."
        r.decision, r.pending = None, None
    return r


def judge_push_out(game: Game, seat: int, facts: ShotFacts) -> Ruling:
    """A push out: no ball need be hit and no rail reached; a scratch is still a foul.
    Balls pocketed stay down, but a 9 is spotted; then the opponent shoots or passes."""
    name, opp = game.players[seat], 1 - seat
    r = Ruling()
    if facts.scratch:
        r.fouls.append(fouls.scratch(name))
    if NINE in facts.pocketed:
        r.spot = (NINE,)
    if r.fouls:
        r.ball_in_hand = ANYWHERE
        return r
    r.notes.append(f"{name} pushed out.")
    r.pending = "push_out"
    r.decision = Decision(opp, PUSH_OUT_OPTIONS,
                          f"{game.players[opp]}, shoot from here or pass the shot back "
                          f"to {name}?")
    return r


def judge_shot(game: Game, seat: int, facts: ShotFacts) -> Ruling:
    """The break (the 1 first, then a ball pocketed or four to a rail) or any later shot
    (the lowest ball first, then a ball pocketed or a rail)."""
    name = game.players[seat]
    lowest = lowest_ball(game.balls)
    r = Ruling()
    if facts.first_contact is None:
        r.fouls.append(fouls.no_contact(name))
    else:
        if facts.first_contact != lowest:
            r.fouls.append(fouls.wrong_ball_first(name, facts.first_contact,
                                                  ball(lowest or NINE)))
        if (not game.breaking and not facts.rail_after_contact
                and not facts.any_pocketed):
            r.fouls.append(fouls.no_rail(name))
    if game.breaking and not facts.any_pocketed and len(facts.balls_to_rail) < 4:
        r.fouls.append(fouls.illegal_break(name, len(facts.balls_to_rail)))
    if facts.scratch:
        r.fouls.append(fouls.scratch(name))
    r.push_out_next = game.breaking
    if NINE in facts.pocketed:
        if r.fouls:
            r.spot = (NINE,)
        else:
            how = ("on the break" if game.breaking else
                   "in a combination" if facts.first_contact != NINE else "")
            r.winner = seat
            r.reason = f"{name} pocketed the 9 {how}".rstrip() + "."
            return r
    if r.fouls:
        r.ball_in_hand = ANYWHERE
    else:
        r.continues = facts.any_pocketed
    return r
