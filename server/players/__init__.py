"""Players: profiles without passwords, Glicko-2 ratings per game kind, the Play now queue.

Pure: no I/O, no asyncio, no clock (times are passed in). `server.ladder` (Play now, ranked
results) and `api.players` drive it; `store.players` keeps its records.
"""

from .glicko2 import Rating, expected_score, idle, rate
from .pool import MatchPool, Pairing, QueueError, Waiting, Window
from .profile import (
    BadName,
    Player,
    check_name,
    default_name,
    new_player_id,
    new_secret,
    seat_key,
    seat_token,
    secret_hash,
)
from .ratings import (
    COMPUTER_RATINGS,
    COUNTED_GAMES,
    PROVISIONAL_RD,
    RANKED_KINDS,
    RATING_PERIOD,
    KindRating,
    Standing,
    counts,
    nearest_level,
    rate_match,
    rate_ranked,
    standings,
)

__all__ = [
    "COMPUTER_RATINGS",
    "COUNTED_GAMES",
    "PROVISIONAL_RD",
    "RANKED_KINDS",
    "RATING_PERIOD",
    "BadName",
    "KindRating",
    "MatchPool",
    "Pairing",
    "Player",
    "QueueError",
    "Rating",
    "Standing",
    "Waiting",
    "Window",
    "check_name",
    "counts",
    "default_name",
    "expected_score",
    "idle",
    "nearest_level",
    "new_player_id",
    "new_secret",
    "rate",
    "rate_match",
    "rate_ranked",
    "seat_key",
    "seat_token",
    "secret_hash",
    "standings",
]
