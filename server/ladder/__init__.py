"""The ladder: Play now's matchmaking, the rating of ranked results and the players'
records, as services the routes call (no HTTP here). `server.players` is its pure core
(Glicko-2, the queue, profiles).

Play now has one interface, `PlayNow`, with two queues behind it: `Matchmaker` (in this
process) and `ClusterMatchmaker` (in Redis, cluster mode); the app picks one.
"""

from .cluster_matchmaker import ClusterMatchmaker
from .friends import RankedTables
from .guests import GuestPruning
from .matchmaker import Matchmaker
from .player_data import PlayerData, RankedRoom, rate_in_store
from .playnow import Assignment, PlayNow, matched
from .results import RankedResults
from .watch import RankedWatch

__all__ = [
    "Assignment",
    "ClusterMatchmaker",
    "GuestPruning",
    "Matchmaker",
    "PlayNow",
    "PlayerData",
    "RankedResults",
    "RankedRoom",
    "RankedTables",
    "RankedWatch",
    "matched",
    "rate_in_store",
]
