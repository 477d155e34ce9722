"""8-ball, WPA World Standardized Rules, judged from a position and a shot's facts.

A ball driven off the table is a foul (WPA General Rules) and stays off, but the 8: off
the table after the break it loses the game (WPA 8-ball, "loss of game"), on the break it
is spotted as when it drops there.

Only the 8 is called (its pocket); other balls count wherever they drop. Three fouls in a
row are no loss in WPA 8-ball, so nothing here counts them.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

from typing_extensions import override

from . import fouls
from .clock import time_foul
from .outcome import ANYWHERE, BEHIND_HEAD_STRING, Decision
from .position import Position
from .ruling import Ruling
from .shotfacts import ShotFacts
from .strategy import GameRules
from .words import pocket

EIGHT = 8
SOLIDS = frozenset(range(1, 8))
STRIPES = frozenset(range(9, 16))
GROUPS = {"solids": SOLIDS, "stripes": STRIPES}
OTHER = {"solids": "stripes", "stripes": "solids"}

SPOT_OR_RERACK = ("spot", "rerack")
ILLEGAL_BREAK_OPTIONS = ("accept", "rerack", "rerack_opponent_breaks")


def group_of(ball_id: int) -> str | None:
    if ball_id in SOLIDS:
        return "solids"
    if ball_id in STRIPES:
        return "stripes"
    return None


def group_left(on_table: Iterable[int], group: str) -> list[int]:
    """Balls of `group` still on the table."""
    members = GROUPS[group]
    return sorted([b for b in on_table if b in members])


def on_eight(on_table: Sequence[int], groups: Sequence[str] | None, seat: int) -> bool:
    """The 8 is `seat`'s legal object: the own group is cleared (or, on an open table, no
    solid or stripe is left at all)."""
    if groups is None:
        return not (group_left(on_table, "solids") or group_left(on_table, "stripes"))
    return not group_left(on_table, groups[seat])


def legal_targets(on_table: Sequence[int], groups: Sequence[str] | None, seat: int) -> list[int]:
    """Balls `seat` may hit first (the 8 is never a legal first ball on an open table)."""
    if on_eight(on_table, groups, seat):
        return [EIGHT] if EIGHT in on_table else []
    if groups is None:
        return group_left(on_table, "solids") + group_left(on_table, "stripes")
    return group_left(on_table, groups[seat])


def break_ball_in_hand(pos: Position) -> str:
    """Ball in hand after a break scratch: anywhere (WPA), or behind the head string."""
    return BEHIND_HEAD_STRING if pos.options.break_scratch_behind_head_string else ANYWHERE


def judge(pos: Position, facts: ShotFacts) -> Ruling:
    return judge_break(pos, facts) if pos.breaking else judge_shot(pos, facts)


def judge_break(pos: Position, facts: ShotFacts) -> Ruling:
    """Legal break: a ball pocketed or four object balls to a rail. The 8 on the break is
    not a loss: spot it or re-rack. The table stays open whatever dropped."""
    seat, opp = pos.turn, pos.opponent
    name, opp_name = pos.shooter, pos.players[opp]
    r = Ruling()
    if facts.scratch:
        r.fouls.append(fouls.scratch(name, facts.cue_off_table))
    if facts.off_table:
        r.fouls.append(fouls.ball_off_table(name, facts.off_table))
        if EIGHT in facts.off_table:
            r.spot = (EIGHT,)
    if EIGHT in facts.pocketed:
        r.pending = "eight_on_break"
        r.notes.append(f"{name} pocketed the 8 on the break.")
        if facts.scratch:
            r.ball_in_hand = break_ball_in_hand(pos)
            r.decision = Decision(
                opp,
                SPOT_OR_RERACK,
                f"{opp_name}, spot the 8 and shoot with ball in hand, or re-rack and break?",
            )
        else:
            r.continues = True
            r.decision = Decision(
                seat,
                SPOT_OR_RERACK,
                f"{name}, spot the 8 and keep shooting, or re-rack and break again?",
            )
        return r
    if not facts.any_pocketed and len(facts.balls_to_rail) < 4:
        r.fouls.append(fouls.illegal_break(name, len(facts.balls_to_rail)))
        r.pending = "illegal_break"
        r.ball_in_hand = break_ball_in_hand(pos) if facts.scratch else None
        r.decision = Decision(
            opp,
            ILLEGAL_BREAK_OPTIONS,
            f"{opp_name}, accept the table and shoot, re-rack and break, "
            f"or re-rack and let {name} break again?",
        )
        return r
    r.notes.append("Legal break. The table is open.")
    if facts.scratch:
        r.ball_in_hand = break_ball_in_hand(pos)
    elif r.fouls:
        r.ball_in_hand = ANYWHERE
    else:
        r.continues = facts.any_pocketed
    return r


def judge_shot(pos: Position, facts: ShotFacts) -> Ruling:
    """Any shot after the break."""
    seat, opp, name = pos.turn, pos.opponent, pos.shooter
    group = pos.groups[seat] if pos.groups else None
    was_on_eight = on_eight(pos.on_table, pos.groups, seat)
    r = Ruling()
    if facts.first_contact is None:
        r.fouls.append(fouls.no_contact(name))
    else:
        if facts.first_contact not in legal_targets(pos.on_table, pos.groups, seat):
            expected = "the 8" if was_on_eight else _group_words(group)
            r.fouls.append(fouls.wrong_ball_first(name, facts.first_contact, expected))
        if not facts.rail_after_contact and not facts.any_pocketed:
            r.fouls.append(fouls.no_rail(name))
    if facts.scratch:
        r.fouls.append(fouls.scratch(name, facts.cue_off_table))
    if facts.off_table:
        r.fouls.append(fouls.ball_off_table(name, facts.off_table))
        if EIGHT in facts.off_table:
            r.winner, r.reason = opp, f"{name} drove the 8 off the table."
            return r

    if EIGHT in facts.pocketed:
        return _eight_dropped(pos, facts, r, was_on_eight)
    if r.fouls:
        r.ball_in_hand = ANYWHERE
        return r
    objects = facts.pocketed
    if group is None:
        if objects:
            taken = group_of(objects[0])
            assert taken is not None
            r.groups = {seat: taken, opp: OTHER[taken]}
            r.notes.append(f"{name} takes the {taken}; {pos.players[opp]} has the {OTHER[taken]}.")
            r.continues = True
    else:
        r.continues = any(b in GROUPS[group] for b in objects)
    return r


def _group_words(group: str | None) -> str:
    return f"one of the {group}" if group else "a solid or a stripe"


def _eight_dropped(pos: Position, facts: ShotFacts, r: Ruling, was_on_eight: bool) -> Ruling:
    """The 8 went down after the break: the game is won or lost on this shot."""
    seat, opp, name = pos.turn, pos.opponent, pos.shooter
    dropped_in = facts.pockets.get(EIGHT, -1)
    called = pos.called_pocket
    if not was_on_eight:
        group = pos.groups[seat] if pos.groups else None
        cleared = f"the {group}" if group else "a group"
        r.winner, r.reason = opp, f"{name} pocketed the 8 before clearing {cleared}."
    elif any(f.code == "scratch" for f in r.fouls):
        r.winner, r.reason = opp, f"{name} scratched while pocketing the 8."
    elif r.fouls:
        r.winner, r.reason = opp, f"{name} fouled while pocketing the 8."
    elif dropped_in != called:
        said = pocket(pos.table, called) if called is not None else "no pocket"
        r.winner = opp
        r.reason = (
            f"{name} pocketed the 8 in the {pocket(pos.table, dropped_in)}, not the called {said}."
        )
    else:
        r.winner = seat
        r.reason = f"{name} pocketed the 8 in the called {pocket(pos.table, dropped_in)}."
    return r


class EightBallRules(GameRules):
    """8-ball as a `GameRules` strategy."""

    kind = "eight_ball"
    seats = 2
    rack = "eight_ball"
    breaks = True
    opening_ball_in_hand = BEHIND_HEAD_STRING
    rerack_at_will = False
    spot_choice = (EIGHT,)

    @override
    def legal_targets(self, pos: Position) -> list[int]:
        return legal_targets(pos.on_table, pos.groups, pos.turn)

    @override
    def balls_left(self, pos: Position) -> list[list[int]] | None:
        """Per seat, its group's balls on the table, once the groups are decided."""
        if not pos.groups:
            return None
        return [group_left(pos.on_table, group) for group in pos.groups]

    @override
    def requires_call(self, pos: Position) -> bool:
        """The shooter is on the 8 and must call its pocket (never on the break)."""
        return not pos.breaking and on_eight(pos.on_table, pos.groups, pos.turn)

    @override
    def judge(self, pos: Position, facts: ShotFacts) -> Ruling:
        return judge(pos, facts)

    @override
    def timeout(self, pos: Position) -> Ruling:
        return time_foul(pos)

    @override
    def count_fouls(self, fouls_in_row: Sequence[int], seat: int, fouled: bool) -> list[int]:
        """WPA 8-ball does not count fouls in a row: the count stays as it is."""
        return list(fouls_in_row)

    @override
    def foul_warning(self, fouls_in_row: Sequence[int], seat: int, name: str) -> str | None:
        return None
