"""`Ruling`: what a game's rules decided about one shot, before the game applies it.

The strategies (`kinds.GameRules`) only judge a frozen `Position`; `Game` owns the state and
applies the ruling, so every kind of game changes state the same way.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .carom_score import CaromScore
from .outcome import Decision, Foul
from .snooker_score import FrameScore


@dataclass
class Ruling:
    """fouls: every foul. continues: the shooter stays (ignored when there are fouls).
    winner / reason: the game ends. spot: object balls to put back on the table.
    groups: groups decided on this shot (8-ball). decision / pending: a choice to make now
    and its kind ("eight_on_break", "illegal_break", "push_out"). ball_in_hand: for the
    next player (or once the decision is taken). notes: sentences to show.
    push_out_next: 9-ball, the next shot may be a push out. break_passes_to: the next shot
    is a break again, by this seat (the shot clock ran out on the break).
    score: the frame's points after the shot (snooker). miss: the foul was a miss, so the
    balls may be replaced (snooker). carom: the game's score after the shot (three-cushion).
    """

    fouls: list[Foul] = field(default_factory=list)
    continues: bool = False
    winner: int | None = None
    reason: str | None = None
    spot: tuple[int, ...] = ()
    groups: dict[int, str] | None = None
    decision: Decision | None = None
    pending: str | None = None
    ball_in_hand: str | None = None
    notes: list[str] = field(default_factory=list)
    push_out_next: bool = False
    break_passes_to: int | None = None
    score: FrameScore | None = None
    miss: bool = False
    carom: CaromScore | None = None
