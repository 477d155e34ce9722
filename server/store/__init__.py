"""Storage (issue 7): match history and restart recovery in SQLite (stdlib `sqlite3`).

`Database` owns one connection on its own thread (every read and write runs there in order,
so the event loop never waits on the disk); `Repository` has the typed queries;
`StoreObserver` records what rooms do; `snapshot` turns a room into JSON and back;
`replay` re-simulates a stored shot into the live stream's messages.
"""

from .database import Database, default_db_path
from .recorder import StoreObserver
from .records import GameRecord, MatchRecord, PendingShot, RoomSnapshot, ShotRecord
from .repository import Repository

__all__ = [
    "Database", "GameRecord", "MatchRecord", "PendingShot", "Repository", "RoomSnapshot",
    "ShotRecord", "StoreObserver", "default_db_path",
]
