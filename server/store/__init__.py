"""Storage: match history and the saved live rooms, in SQLite (stdlib `sqlite3`).

`Database` owns one connection on its own thread (every read and write runs there in order,
so the event loop never waits on the disk); `Repository` has the typed queries; `records`
the typed rows. It stores and loads records only: turning rooms into records and back is
the rooms' job.
"""

from .database import Database
from .records import GameRecord, MatchRecord, PendingShot, RoomSnapshot, ShotRecord
from .repository import Repository

__all__ = [
    "Database",
    "GameRecord",
    "MatchRecord",
    "PendingShot",
    "Repository",
    "RoomSnapshot",
    "ShotRecord",
]
