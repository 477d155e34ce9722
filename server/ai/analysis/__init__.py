"""Analysis of a finished match: every stored shot against the pro level's best choice.

Pure, like the rest of `server.ai`: stored rows in (`StoredShot`), a `MatchAnalysis` out,
the same on every run (seeds from the match and shot ids). `rebuild` plays the stored
strokes forward to get the game before each shot, `judge` values the played stroke and the
pro's on the same draws, `verdicts` turns the loss of winning chance into words and an
accuracy (thresholds documented there and in docs/ai.md).
"""

from .judge import (
    DRAWS,
    LEVEL,
    BestShot,
    MatchAnalysis,
    PlayerSummary,
    ShotVerdict,
    analyse_match,
    judge_shot,
    shot_seed,
    summarise,
)
from .rebuild import Before, StoredShot, positions
from .verdicts import BEST, GOOD, MISTAKE, VERDICTS
from .worker import judge_nth

__all__ = [
    "BEST",
    "DRAWS",
    "GOOD",
    "LEVEL",
    "MISTAKE",
    "VERDICTS",
    "Before",
    "BestShot",
    "MatchAnalysis",
    "PlayerSummary",
    "ShotVerdict",
    "StoredShot",
    "analyse_match",
    "judge_nth",
    "judge_shot",
    "positions",
    "shot_seed",
    "summarise",
]
