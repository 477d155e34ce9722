"""Practice: one player, ball in hand anywhere at all times, no fouls, never over; on the
pool table ("practice") or the snooker table ("snooker_practice")."""

from __future__ import annotations

from collections.abc import Sequence

from typing_extensions import override

from server.engine import Table

from .outcome import ANYWHERE
from .position import Position
from .ruling import Ruling
from .shotfacts import ShotFacts
from .strategy import GameRules
from .words import and_list, snooker_ball


class PracticeRules(GameRules):
    """Practice as a `GameRules` strategy: every shot is legal and the player stays."""

    kind = "practice"
    seats = 1
    rack = "eight_ball"
    breaks = False
    opening_ball_in_hand = ANYWHERE
    rerack_at_will = True
    spot_choice: tuple[int, ...] = ()

    @override
    def legal_targets(self, pos: Position) -> list[int]:
        """Empty: anything goes."""
        return []

    @override
    def balls_left(self, pos: Position) -> list[list[int]] | None:
        return None

    @override
    def requires_call(self, pos: Position) -> bool:
        return False

    @override
    def judge(self, pos: Position, facts: ShotFacts) -> Ruling:
        """No fouls; a pocketed cue ball comes back as ball in hand."""
        r = Ruling(continues=True, ball_in_hand=ANYWHERE)
        if facts.scratch:
            r.notes.append("The cue ball went in: place it anywhere.")
        if not [b for b in pos.object_balls if b not in facts.pocketed]:
            r.notes.append("Table cleared. Rerack to play again.")
        return r

    @override
    def timeout(self, pos: Position) -> Ruling:
        """Nothing happens but the message: there is no one to pass the turn to."""
        return Ruling(continues=True, ball_in_hand=ANYWHERE, notes=["Time ran out."])

    @override
    def count_fouls(self, fouls_in_row: Sequence[int], seat: int, fouled: bool) -> list[int]:
        return list(fouls_in_row)

    @override
    def foul_warning(self, fouls_in_row: Sequence[int], seat: int, name: str) -> str | None:
        return None


class SnookerPracticeRules(PracticeRules):
    """Practice on the snooker table with its 22 balls: the same freedom (no fouls, ball in
    hand anywhere)."""

    kind = "snooker_practice"
    rack = "snooker"

    @override
    def table(self) -> Table:
        return Table.snooker()

    @override
    def ball_names(self, ball_ids: Sequence[int]) -> str:
        return and_list(snooker_ball(b) for b in ball_ids)


PRACTICE_KINDS = ("practice", "snooker_practice", "three_cushion_practice")
