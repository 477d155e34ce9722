"""`Position`: what the rules may read about a game, frozen.

The judges and the strategies see this copy, never the mutable `Game`, so a ruling can
only be a function of the position and the shot; `Game` alone changes state.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from server.engine import CUE, BallSet, Table

from .carom_score import CaromScore
from .options import RuleOptions
from .snooker_score import FrameScore


@dataclass(frozen=True)
class Position:
    """The table at rest before a shot and the state of the game around it.

    players: names by seat. on_table: ids of the balls on the table (the cue ball
    included), in the ball set's order. turn: the seat to shoot. breaking: the next shot
    is the break. groups: 8-ball, the group of each seat once decided. fouls_in_row: per
    seat. called_pocket: 8-ball, the pocket called for the 8. push_out_declared: 9-ball,
    the next shot is a push out. score: snooker, the frame's points, break and ball on.
    balls: the table at rest (the referee's eye: whether the striker is snookered).
    carom: three-cushion, the game's points, innings and runs.
    """

    players: tuple[str, ...]
    table: Table
    options: RuleOptions
    on_table: tuple[int, ...]
    turn: int
    breaking: bool = False
    groups: tuple[str, ...] | None = None
    fouls_in_row: tuple[int, ...] = ()
    called_pocket: int | None = None
    push_out_declared: bool = False
    score: FrameScore | None = None
    balls: BallSet | None = field(default=None, compare=False, repr=False)
    carom: CaromScore | None = None

    @property
    def shooter(self) -> str:
        return self.players[self.turn]

    @property
    def opponent(self) -> int:
        return 1 - self.turn

    @property
    def object_balls(self) -> list[int]:
        """The balls on the table other than the cue ball, in the ball set's order."""
        return [b for b in self.on_table if b != CUE]
