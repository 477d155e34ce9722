"""`Game`: one rack of 8-ball, 9-ball or practice, in the spirit of python-chess's `Board`.

Pure: no I/O. It knows the players, whose turn it is, the table at rest and what is legal
now; `apply` takes the engine's `ShotResult` and returns an `Outcome`. Every action that is
not allowed raises `IllegalActionError` and changes nothing.
"""

from __future__ import annotations

from server.engine import BallSet, ShotResult, Table

from .options import DEFAULT_OPTIONS, RuleOptions
from .outcome import Decision, Outcome


class Game:
    """One rack (players call it a frame; `Frame` is the engine's per-tick snapshot)."""

    def __init__(self, kind: str, players: tuple[str, str] | tuple[str], breaker: int = 0,
                 table: Table | None = None, seed: int = 0,
                 options: RuleOptions = DEFAULT_OPTIONS) -> None:
        raise NotImplementedError

    kind: str
    table: Table
    players: tuple[str, ...]
    balls: BallSet
    turn: int
    ball_in_hand: str | None
    groups: dict[int, str] | None
    called_pocket: int | None
    decision: Decision | None
    over: bool
    winner: int | None
    reason: str | None
    last_outcome: Outcome | None

    @property
    def requires_call(self) -> bool:
        """8-ball: the shooter is on the 8 and must call its pocket before shooting."""
        raise NotImplementedError

    def check_shot(self, seat: int) -> None:
        """Raise `IllegalActionError` unless `seat` may shoot now."""
        raise NotImplementedError

    def can_place_cue(self, x: float, y: float) -> bool:
        """True when the player with ball in hand may put the cue ball at (x, y)."""
        raise NotImplementedError

    def place_cue(self, seat: int, x: float, y: float) -> None:
        """Ball in hand: put the cue ball at (x, y); may be repeated before the shot."""
        raise NotImplementedError

    def call_pocket(self, seat: int, pocket: int) -> None:
        """8-ball: name the pocket (index into `table.pockets`) for the 8."""
        raise NotImplementedError

    def declare_push_out(self, seat: int) -> None:
        """9-ball: announce a push out for the shot right after the break."""
        raise NotImplementedError

    def decide(self, seat: int, option: str) -> None:
        """Answer the pending `decision` with one of its options."""
        raise NotImplementedError

    def apply(self, seat: int, result: ShotResult) -> Outcome:
        """Judge a simulated shot (after `check_shot` passed) and move the game on."""
        raise NotImplementedError

    def timeout(self, seat: int) -> Outcome:
        """The shot clock ran out for `seat`: a foul, the turn passes."""
        raise NotImplementedError

    def resign(self, seat: int, reason: str) -> Outcome:
        """`seat` loses this game (concession or forfeit); `reason` is a sentence."""
        raise NotImplementedError

    def rerack(self) -> None:
        """Practice only: rack the balls again."""
        raise NotImplementedError

    def public_state(self) -> dict:
        """JSON-able: everything a client shows."""
        raise NotImplementedError
