"""The shot clock running out in a two-player game: a foul like any other, except on the
break, where the break passes to the opponent."""

from __future__ import annotations

from . import fouls
from .outcome import ANYWHERE, BEHIND_HEAD_STRING
from .position import Position
from .ruling import Ruling


def time_foul(pos: Position) -> Ruling:
    """Ball in hand anywhere for the opponent; on the break, the opponent breaks instead,
    from behind the head string."""
    r = Ruling(fouls=[fouls.shot_clock(pos.shooter)], ball_in_hand=ANYWHERE)
    if pos.breaking:
        r.break_passes_to = pos.opponent
        r.ball_in_hand = BEHIND_HEAD_STRING
        r.notes.append(f"{pos.players[pos.opponent]} breaks instead.")
    return r
