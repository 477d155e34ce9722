"""The computer opponent: shot search with the engine under each level's execution noise.

Pure: no I/O, no asyncio; imports only `server.engine`, `server.rules` and `server.codec`.
`Bot(level, seed).plan(game, seat) -> Turn`; `Bot.execute(shot, rng) -> Shot` is the
level's execution error, which the room applies; `play_turn` applies a turn to a game
through the rules' actions. See docs/ai.md.
"""

from .bot import Bot, Turn
from .levels import LEVEL_TABLE, LEVELS, Level
from .play import play_turn

__all__ = ["LEVELS", "LEVEL_TABLE", "Bot", "Level", "Turn", "play_turn"]
