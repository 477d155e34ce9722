"""One strategy per kind of game: everything `Game` would otherwise ask its `kind` about.

`Game` holds the state and applies rulings; a `GameRules` reads a frozen `Position` and
says what is legal and what a shot or a timeout means. Adding a kind of game is adding a
strategy here, not another branch in `Game`.
"""

from __future__ import annotations

from .eight_ball import EightBallRules
from .nine_ball import NineBallRules
from .practice import PracticeRules, SnookerPracticeRules
from .snooker import SnookerRules
from .strategy import GameRules
from .three_cushion import ThreeCushionPracticeRules, ThreeCushionRules

STRATEGIES: tuple[GameRules, ...] = (
    EightBallRules(),
    NineBallRules(),
    PracticeRules(),
    SnookerRules(),
    SnookerPracticeRules(),
    ThreeCushionRules(),
    ThreeCushionPracticeRules(),
)
RULES: dict[str, GameRules] = {rules.kind: rules for rules in STRATEGIES}
GAME_KINDS = tuple(RULES)


def rules_for(kind: str) -> GameRules:
    """The strategy of `kind`; ValueError for a kind that does not exist."""
    try:
        return RULES[kind]
    except KeyError:
        raise ValueError(f"unknown game {kind!r}; choose one of {GAME_KINDS}") from None
