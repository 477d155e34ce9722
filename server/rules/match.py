"""`Match`: a race to N games with the break alternating between the players."""

from __future__ import annotations

from server.engine import ShotResult, Table

from .game import Game
from .options import DEFAULT_OPTIONS, RuleOptions
from .outcome import Outcome


class Match:
    """A race to `race_to` games; the break alternates, seat `first_breaker` breaks first."""

    def __init__(self, kind: str, players: tuple[str, str] | tuple[str], race_to: int = 1,
                 seed: int = 0, options: RuleOptions = DEFAULT_OPTIONS,
                 table: Table | None = None, first_breaker: int = 0) -> None:
        raise NotImplementedError

    kind: str
    race_to: int
    players: tuple[str, ...]
    score: list[int]
    game: Game
    over: bool
    winner: int | None

    def apply(self, seat: int, result: ShotResult) -> Outcome:
        """Judge a shot in the current game and keep the score."""
        raise NotImplementedError

    def timeout(self, seat: int) -> Outcome:
        raise NotImplementedError

    def concede(self, seat: int) -> Outcome:
        """`seat` loses the current game."""
        raise NotImplementedError

    def forfeit(self, seat: int, reason: str) -> Outcome:
        """`seat` loses the match (e.g. left and did not come back)."""
        raise NotImplementedError

    def next_game(self) -> Game:
        """Rack the next game once the current one is over and the match is not."""
        raise NotImplementedError

    def rematch(self) -> None:
        """A new match between the same players, score 0-0."""
        raise NotImplementedError

    def public_state(self) -> dict:
        raise NotImplementedError
