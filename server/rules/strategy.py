"""The interface of a kind of game's rules: everything `Game` would otherwise ask its `kind`
about. The strategies subclass it, so a type checker holds each to its signatures."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Protocol

from server.engine import CUE, BallSet, Table

from . import spotting, words
from .carom_score import CaromScore
from .position import Position
from .ruling import Ruling
from .shotfacts import ShotFacts
from .snooker_score import FrameScore


class GameRules(Protocol):
    """The rules of one kind of game. Stateless: every answer is a function of its
    arguments, so one instance serves every game of its kind."""

    @property
    def kind(self) -> str:
        """The kind string this strategy is registered under (`Game.kind`)."""
        ...

    @property
    def seats(self) -> int:
        """How many players the game takes."""
        ...

    @property
    def rack(self) -> str:
        """The engine's rack to set up (`server.engine.rack`)."""
        ...

    @property
    def breaks(self) -> bool:
        """A rack starts with a break (judged by the break rules)."""
        ...

    @property
    def opening_ball_in_hand(self) -> str | None:
        """Where the cue ball may go for a rack's first shot (None: it stays on its spot)."""
        ...

    @property
    def rerack_at_will(self) -> bool:
        """The player may re-rack whenever they like (`Game.rerack`)."""
        ...

    @property
    def spot_choice(self) -> tuple[int, ...]:
        """The balls the decision option "spot" puts back on the table."""
        ...

    def legal_targets(self, pos: Position) -> list[int]:
        """Balls the shooter may hit first now (empty: any ball)."""
        ...

    def balls_left(self, pos: Position) -> list[list[int]] | None:
        """Per seat, the balls that seat still has to pocket; None when not shown."""
        ...

    def requires_call(self, pos: Position) -> bool:
        """The shooter must call a pocket before shooting."""
        ...

    def judge(self, pos: Position, facts: ShotFacts) -> Ruling:
        """The ruling on a shot played by `pos.turn` from `pos`; a push out is judged as
        one when `pos.push_out_declared`, and a ruling's `push_out_next` offers the next."""
        ...

    def timeout(self, pos: Position) -> Ruling:
        """The ruling when the shot clock runs out on `pos.turn`."""
        ...

    def count_fouls(self, fouls_in_row: Sequence[int], seat: int, fouled: bool) -> list[int]:
        """Fouls in a row per seat once `seat` has played a shot, fouled or not."""
        ...

    def foul_warning(self, fouls_in_row: Sequence[int], seat: int, name: str) -> str | None:
        """A sentence warning `seat` (called `name`) about its count, if it needs one."""
        ...

    # The pool kinds share these answers; snooker gives its own.
    def table(self) -> Table:
        """The table a game of this kind is played on unless told otherwise."""
        return Table.pool("9ft")

    def new_score(self, seats: int) -> FrameScore | None:  # noqa: ARG002 - pool keeps none
        """The points kept in a frame (snooker), None for a game won by its last ball."""
        return None

    def new_carom(self, opener: int) -> CaromScore | None:  # noqa: ARG002 - pool keeps none
        """The score of a carom game opened by `opener` (three-cushion), None otherwise."""
        return None

    def cue_ball(self, pos: Position) -> int:  # noqa: ARG002 - pool has one cue ball
        """The ball the striker strikes (carom: the striker's white or yellow)."""
        return CUE

    def nominations(self, pos: Position) -> list[int]:  # noqa: ARG002 - pool has none
        """The balls the striker may nominate now (snooker: a colour, a free ball)."""
        return []

    def ball_names(self, ball_ids: Sequence[int]) -> str:
        """'the 3 and the 9': the balls as players name them."""
        return words.balls(ball_ids)

    def respot(self, table: Table, balls: BallSet, ball_ids: tuple[int, ...]) -> BallSet:
        """`balls` with `ball_ids` put back on the table (pool: the foot spot)."""
        return spotting.respot(table, balls, ball_ids)
