"""`Ruling`: what a game's rules decided about one shot, before the game applies it.

The rule modules (`eight_ball`, `nine_ball`) only judge; `Game` owns the state and applies
the ruling, so every kind of game changes state the same way.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from .outcome import Decision, Foul


@dataclass
class Ruling:
    """fouls: every foul. continues: the shooter stays (ignored when there are fouls).
    winner / reason: the game ends. spot: object balls to put back on the table.
    groups: groups decided on this shot (8-ball). decision / pending: a choice to make now
    and its kind ("eight_on_break", "illegal_break", "push_out"). ball_in_hand: for the
    next player (after fouls, or once the decision is taken). notes: sentences to show.
    push_out_next: 9-ball, the next shot may be a push out.
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
