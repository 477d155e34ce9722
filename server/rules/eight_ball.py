"""8-ball, WPA World Standardized Rules, judged from a shot's facts.

Only the 8 is called (its pocket); other balls count wherever they drop. Three fouls in a
row are no loss in WPA 8-ball, so nothing here counts them.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from server.engine import BallSet

from . import fouls
from .outcome import ANYWHERE, BEHIND_HEAD_STRING, Decision
from .ruling import Ruling
from .shotfacts import ShotFacts
from .words import pocket

if TYPE_CHECKING:
    from .game import Game

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


def group_left(balls: BallSet, group: str) -> list[int]:
    """Balls of `group` still on the table."""
    return sorted(b for b in balls.on_table_ids() if b in GROUPS[group])


def on_eight(balls: BallSet, groups: dict[int, str] | None, seat: int) -> bool:
    """The 8 is `seat`'s legal object: the own group is cleared (or, on an open table, no
    solid or stripe is left at all)."""
    if groups is None:
        return not (group_left(balls, "solids") or group_left(balls, "stripes"))
    return not group_left(balls, groups[seat])


def legal_targets(balls: BallSet, groups: dict[int, str] | None, seat: int) -> list[int]:
    """Balls `seat` may hit first (the 8 is never a legal first ball on an open table)."""
    if on_eight(balls, groups, seat):
        return [EIGHT] if EIGHT in balls.on_table_ids() else []
    if groups is None:
        return group_left(balls, "solids") + group_left(balls, "stripes")
    return group_left(balls, groups[seat])


def break_ball_in_hand(game: Game) -> str:
    """Ball in hand after a break scratch: anywhere (WPA), or behind the head string."""
    return BEHIND_HEAD_STRING if game.options.break_scratch_behind_head_string else ANYWHERE


def judge(game: Game, seat: int, facts: ShotFacts) -> Ruling:
    return judge_break(game, seat, facts) if game.breaking else judge_shot(game, seat, facts)


def judge_break(game: Game, seat: int, facts: ShotFacts) -> Ruling:
    """Legal break: a ball pocketed or four object balls to a rail. The 8 on the break is
    not a loss: spot it or re-rack. The table stays open whatever dropped."""
    name, opp = game.players[seat], 1 - seat
    opp_name = game.players[opp]
    r = Ruling()
    if facts.scratch:
        r.fouls.append(fouls.scratch(name))
    if EIGHT in facts.pocketed:
        r.pending = "eight_on_break"
        r.notes.append(f"{name} pocketed the 8 on the break.")
        if facts.scratch:
            r.ball_in_hand = break_ball_in_hand(game)
            r.decision = Decision(opp, SPOT_OR_RERACK,
                                  f"{opp_name}, spot the 8 and shoot with ball in hand, "
                                  "or re-rack and break?")
        else:
            r.continues = True
            r.decision = Decision(seat, SPOT_OR_RERACK,
                                  f"{name}, spot the 8 and keep shooting, "
                                  "or re-rack and break again?")
        return r
    if not facts.any_pocketed and len(facts.balls_to_rail) < 4:
        r.fouls.append(fouls.illegal_break(name, len(facts.balls_to_rail)))
        r.pending = "illegal_break"
        r.ball_in_hand = break_ball_in_hand(game) if facts.scratch else None
        r.decision = Decision(opp, ILLEGAL_BREAK_OPTIONS,
                              f"{opp_name}, accept the table and shoot, re-rack and break, "
                              f"or re-rack and let {name} break again?")
        return r
    r.notes.append("Legal break. The table is open.")
    if facts.scratch:
        r.ball_in_hand = break_ball_in_hand(game)
    else:
        r.continues = facts.any_pocketed
    return r


def judge_shot(game: Game, seat: int, facts: ShotFacts) -> Ruling:
    """Any shot after the break."""
    name, opp = game.players[seat], 1 - seat
    groups = game.groups
    group = groups[seat] if groups else None
    was_on_eight = on_eight(game.balls, groups, seat)
    r = Ruling()
    if facts.first_contact is None:
        r.fouls.append(fouls.no_contact(name))
    else:
        if facts.first_contact not in legal_targets(game.balls, groups, seat):
            expected = ("the 8" if was_on_eight else
                        f"one of the {group}" if group else "a solid or a stripe")
            r.fouls.append(fouls.wrong_ball_first(name, facts.first_contact, expected))
        if not facts.rail_after_contact and not facts.any_pocketed:
            r.fouls.append(fouls.no_rail(name))
    if facts.scratch:
        r.fouls.append(fouls.scratch(name))

    if EIGHT in facts.pocketed:
        return _eight_dropped(game, seat, facts, r, was_on_eight)
    if r.fouls:
        r.ball_in_hand = ANYWHERE
        return r
    objects = facts.pocketed
    if group is None:
        if objects:
            taken = group_of(objects[0])
            assert taken is not None
            r.groups = {seat: taken, opp: OTHER[taken]}
            r.notes.append(f"{name} takes the {taken}; {game.players[opp]} has the "
                           f"{OTHER[taken]}.")
            r.continues = True
    else:
        r.continues = any(b in GROUPS[group] for b in objects)
    return r


def _eight_dropped(game: Game, seat: int, facts: ShotFacts, r: Ruling,
                   was_on_eight: bool) -> Ruling:
    """The 8 went down after the break: the game is won or lost on this shot."""
    name, opp = game.players[seat], 1 - seat
    dropped_in = facts.pockets.get(EIGHT, -1)
    if not was_on_eight:
        group = game.groups[seat] if game.groups else None
        cleared = f"the {group}" if group else "a group"
        r.winner, r.reason = opp, f"{name} pocketed the 8 before clearing {cleared}."
    elif any(f.code == "scratch" for f in r.fouls):
        r.winner, r.reason = opp, f"{name} scratched while pocketing the 8."
    elif r.fouls:
        r.winner, r.reason = opp, f"{name} fouled while pocketing the 8."
    elif dropped_in != game.called_pocket:
        called = (pocket(game.table, game.called_pocket)
                  if game.called_pocket is not None else "no pocket")
        r.winner = opp
        r.reason = (f"{name} pocketed the 8 in the {pocket(game.table, dropped_in)}, "
                    f"not the called {called}.")
    else:
        r.winner = seat
        r.reason = f"{name} pocketed the 8 in the called {pocket(game.table, dropped_in)}."
    return r
