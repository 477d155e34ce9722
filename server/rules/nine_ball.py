"""9-ball, WPA World Standardized Rules, judged from a position and a shot's facts.

The lowest-numbered ball must be hit first; any ball pocketed on a legal shot counts; the 9
pocketed legally wins, on the break or in a combination; an illegally pocketed 9 is
re-spotted; three fouls in a row lose. A ball driven off the table is a foul (WPA General
Rules); the 9 driven off is spotted as an illegally pocketed 9 is, the others stay off.
"""

from __future__ import annotations

from collections.abc import Sequence

from typing_extensions import override

from server.engine import CUE

from . import fouls
from .clock import time_foul
from .outcome import ANYWHERE, BEHIND_HEAD_STRING, Decision
from .position import Position
from .ruling import Ruling
from .shotfacts import ShotFacts
from .strategy import GameRules
from .words import ball

NINE = 9
FOULS_TO_LOSE = 3
PUSH_OUT_OPTIONS = ("shoot", "pass")


def lowest_ball(on_table: Sequence[int]) -> int | None:
    on = [b for b in on_table if b != CUE]
    return min(on) if on else None


def judge_push_out(pos: Position, facts: ShotFacts) -> Ruling:
    """A push out: no ball need be hit and no rail reached; a scratch is still a foul.
    Balls pocketed stay down, but a 9 is spotted; then the opponent shoots or passes."""
    name, opp = pos.shooter, pos.opponent
    r = Ruling()
    if facts.scratch:
        r.fouls.append(fouls.scratch(name, facts.cue_off_table))
    _off_table(name, facts, r)
    if NINE in facts.pocketed:
        r.spot = (NINE,)
    if r.fouls:
        r.ball_in_hand = ANYWHERE
        return r
    r.notes.append(f"{name} pushed out.")
    r.pending = "push_out"
    r.decision = Decision(
        opp,
        PUSH_OUT_OPTIONS,
        f"{pos.players[opp]}, shoot from here or pass the shot back to {name}?",
    )
    return r


def judge_shot(pos: Position, facts: ShotFacts) -> Ruling:
    """The break (the 1 first, then a ball pocketed or four to a rail) or any later shot
    (the lowest ball first, then a ball pocketed or a rail)."""
    name, breaking = pos.shooter, pos.breaking
    lowest = lowest_ball(pos.on_table)
    r = Ruling()
    if facts.first_contact is None:
        r.fouls.append(fouls.no_contact(name))
    else:
        if facts.first_contact != lowest:
            r.fouls.append(fouls.wrong_ball_first(name, facts.first_contact, ball(lowest or NINE)))
        if not breaking and not facts.rail_after_contact and not facts.any_pocketed:
            r.fouls.append(fouls.no_rail(name))
    if breaking and not facts.any_pocketed and len(facts.balls_to_rail) < 4:
        r.fouls.append(fouls.illegal_break(name, len(facts.balls_to_rail)))
    if facts.scratch:
        r.fouls.append(fouls.scratch(name, facts.cue_off_table))
    _off_table(name, facts, r)
    r.push_out_next = breaking
    if NINE in facts.pocketed:
        if r.fouls:
            r.spot = (NINE,)
        else:
            if breaking:
                how = " on the break"
            elif facts.first_contact != NINE:
                how = " in a combination"
            else:
                how = ""
            r.winner, r.reason = pos.turn, f"{name} pocketed the 9{how}."
            return r
    if r.fouls:
        r.ball_in_hand = ANYWHERE
    else:
        r.continues = facts.any_pocketed
    return r


def _off_table(name: str, facts: ShotFacts, r: Ruling) -> None:
    """A ball off the table: a foul; the 9 comes back on its spot."""
    if facts.off_table:
        r.fouls.append(fouls.ball_off_table(name, facts.off_table))
        if NINE in facts.off_table:
            r.spot = (NINE,)


def lose_on_last_foul(pos: Position, r: Ruling) -> Ruling:
    """The three-foul rule, for shots and the shot clock alike: a foul that makes
    `FOULS_TO_LOSE` in a row loses the game, whatever else the shot did."""
    if r.fouls and pos.fouls_in_row[pos.turn] + 1 >= FOULS_TO_LOSE:
        r.winner, r.reason = pos.opponent, f"{pos.shooter} fouled three times in a row."
        r.decision, r.pending = None, None
    return r


class NineBallRules(GameRules):
    """9-ball as a `GameRules` strategy."""

    kind = "nine_ball"
    seats = 2
    rack = "nine_ball"
    breaks = True
    opening_ball_in_hand = BEHIND_HEAD_STRING
    rerack_at_will = False
    spot_choice: tuple[int, ...] = ()

    @override
    def legal_targets(self, pos: Position) -> list[int]:
        """The lowest ball; on a push out, any ball."""
        if pos.push_out_declared:
            return pos.object_balls
        lowest = lowest_ball(pos.on_table)
        return [lowest] if lowest is not None else []

    @override
    def balls_left(self, pos: Position) -> list[list[int]] | None:
        """Both seats play the same balls: every object ball on the table."""
        left = pos.object_balls
        return [left, list(left)]

    @override
    def requires_call(self, pos: Position) -> bool:
        return False

    @override
    def judge(self, pos: Position, facts: ShotFacts) -> Ruling:
        judged = judge_push_out if pos.push_out_declared else judge_shot
        return lose_on_last_foul(pos, judged(pos, facts))

    @override
    def timeout(self, pos: Position) -> Ruling:
        """A foul; on the break it passes the break and cannot lose the game."""
        r = time_foul(pos)
        return r if pos.breaking else lose_on_last_foul(pos, r)

    @override
    def count_fouls(self, fouls_in_row: Sequence[int], seat: int, fouled: bool) -> list[int]:
        """A foul adds one to the shooter's count; a legal shot resets it."""
        counts = list(fouls_in_row)
        counts[seat] = counts[seat] + 1 if fouled else 0
        return counts

    @override
    def foul_warning(self, fouls_in_row: Sequence[int], seat: int, name: str) -> str | None:
        if fouls_in_row[seat] == FOULS_TO_LOSE - 1:
            return f"{name} is on two fouls: a third foul in a row loses."
        return None
