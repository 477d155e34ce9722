"""The rules of pool: 8-ball and 9-ball (WPA), practice, and matches (race to N).

Pure Python over the physics engine's `ShotResult` events: no I/O, no asyncio. The names
exported here are the contract with the room (see docs/rules.md).
"""

from .errors import IllegalActionError, RulesError
from .game import Game
from .kinds import GAME_KINDS
from .match import Match
from .options import RuleOptions
from .outcome import ANYWHERE, BEHIND_HEAD_STRING, Decision, Foul, Outcome
from .practice import PRACTICE_KINDS

__all__ = [
    "ANYWHERE",
    "BEHIND_HEAD_STRING",
    "GAME_KINDS",
    "PRACTICE_KINDS",
    "Decision",
    "Foul",
    "Game",
    "IllegalActionError",
    "Match",
    "Outcome",
    "RuleOptions",
    "RulesError",
]
