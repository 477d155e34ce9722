"""`Match`: a race to N games with the break alternating between the players."""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from server.codec import from_data, to_dict
from server.engine import ShotResult, Table

from .errors import IllegalActionError
from .game import Game
from .options import DEFAULT_OPTIONS, RuleOptions
from .outcome import Outcome
from .stored import StoredTable

GAME_SEED_STEP = 1009  # each game of a match gets its own seed, reproducibly


@dataclass(init=False, eq=False)
class Match:
    """A race to `race_to` games; the break alternates, seat `first_breaker` breaks first.

    Practice is a match that never ends: its one game never finishes. The fields are the
    whole state and its stored form (`to_dict`); `table` None means the game's default.
    """

    kind: str
    players: tuple[str, ...]
    race_to: int
    seed: int
    options: RuleOptions
    table: StoredTable | None
    first_breaker: int
    score: list[int]
    over: bool
    winner: int | None
    reason: str | None
    games_played: int
    game: Game

    def __init__(
        self,
        kind: str,
        players: Sequence[str],
        race_to: int = 1,
        seed: int = 0,
        options: RuleOptions = DEFAULT_OPTIONS,
        table: Table | None = None,
        first_breaker: int = 0,
    ) -> None:
        """A new match, its first game racked. (Rooms start matches this way; a stored
        match comes back through `from_dict`, which sets the fields as they were.)"""
        if not isinstance(race_to, int) or isinstance(race_to, bool) or race_to < 1:
            raise ValueError("race_to must be a whole number of games, at least 1")
        self.kind = kind
        self.players = tuple(players)
        self.race_to = race_to
        self.seed = seed
        self.options = options
        self.table = table
        self.first_breaker = first_breaker
        self._start()

    def _start(self) -> None:
        self.score = [0] * len(self.players)
        self.over = False
        self.winner = None
        self.reason = None
        self.games_played = 0
        self.game = self._new_game()

    def _new_game(self) -> Game:
        """Game k (from 0) is broken by the first breaker when k is even, else the other."""
        n = self.games_played
        return Game.new(
            self.kind,
            self.players,
            breaker=(self.first_breaker + n) % len(self.players),
            table=self.table,
            seed=self.seed + GAME_SEED_STEP * n,
            options=self.options,
        )

    def _check_open(self, code: str = "game_over") -> None:
        if self.over:
            raise IllegalActionError(code, "The match is over.")

    def _scored(self, outcome: Outcome, forfeit: str | None = None) -> Outcome:
        """Count a finished game; end the match on reaching the race or on a forfeit."""
        if not outcome.frame_over or outcome.winner is None:
            return outcome
        winner = outcome.winner
        self.score[winner] += 1
        self.games_played += 1
        if self.score[winner] >= self.race_to or forfeit is not None:
            self.over, self.winner = True, winner
            self.reason = forfeit or f"{self.players[winner]} reached {self.race_to}."
            line = (
                f"{self.players[winner]} wins the match "
                f"{self.score[winner]}-{self.score[1 - winner]}."
            )
        else:
            line = f"Score {self.score[0]}-{self.score[1]}."
        return self._relay(dataclasses.replace(outcome, message=f"{outcome.message} {line}"))

    def _relay(self, outcome: Outcome) -> Outcome:
        self.game.last_outcome = outcome
        return outcome

    def apply(self, seat: int, result: ShotResult) -> Outcome:
        """Judge a shot in the current game and keep the score."""
        self._check_open()
        return self._scored(self.game.apply(seat, result))

    def timeout(self, seat: int) -> Outcome:
        self._check_open()
        return self._scored(self.game.timeout(seat))

    def concede(self, seat: int) -> Outcome:
        """`seat` loses the current game."""
        self._check_open()
        name = self.players[seat] if seat in range(len(self.players)) else "?"
        return self._scored(self.game.resign(seat, f"{name} conceded the game."))

    def forfeit_game(self, seat: int, reason: str) -> Outcome:
        """`seat` loses the current game (frame) for `reason`, not by play: e.g. left the
        table and did not come back in time. The match goes on unless that was the race."""
        self._check_open()
        return self._scored(self.game.resign(seat, reason))

    def forfeit(self, seat: int, reason: str) -> Outcome:
        """`seat` loses the match (e.g. left and did not come back); `reason` says why."""
        self._check_open()
        if self.game.over:  # between games: the match ends on the current score
            if len(self.players) != 2 or seat not in (0, 1):
                raise IllegalActionError("not_your_turn", "Only a seated player can forfeit.")
            winner = 1 - seat
            self.over, self.winner, self.reason = True, winner, reason
            return self._relay(
                Outcome(
                    shooter=seat,
                    pocketed=(),
                    fouls=(),
                    continues=False,
                    next_turn=winner,
                    ball_in_hand=None,
                    frame_over=True,
                    winner=winner,
                    reason=reason,
                    message=f"{reason} {self.players[winner]} wins the match.",
                )
            )
        return self._scored(self.game.resign(seat, reason), forfeit=reason)

    def next_game(self) -> Game:
        """Rack the next game once the current one is over and the match is not."""
        self._check_open("match_over")
        if not self.game.over:
            raise IllegalActionError("game_not_over", "The current game is still on.")
        self.game = self._new_game()
        return self.game

    def rematch(self) -> None:
        """A new match between the same players, score 0-0; the other seat breaks first."""
        self.first_breaker = (self.first_breaker + 1) % len(self.players)
        self.seed += 1
        self._start()

    def to_dict(self) -> dict[str, Any]:
        """The stored form, the current game included: `server.codec.to_data(self)`."""
        return to_dict(self)

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Match:
        """The inverse of `to_dict`; also reads what the code before the codec stored."""
        return from_data(cls, data)

    def public_state(self) -> dict[str, Any]:
        """The game's public state plus the score, the race and the match result."""
        state = self.game.public_state()
        state.update(
            {
                "score": list(self.score),
                "race_to": self.race_to,
                "games_played": self.games_played,
                "match_over": self.over,
                "match_winner": self.winner,
                "match_reason": self.reason,
            }
        )
        return state
