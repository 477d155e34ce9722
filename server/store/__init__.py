"""Storage: match history, the saved live rooms and room ownership, in SQLite (default, one
process) or PostgreSQL (shared by several processes), through SQLAlchemy Core; one schema
and one set of Alembic migrations for both (`schema`, `migrate`, `migrations/`).

`Database(target)` owns one connection on its own thread (every call runs there in order,
so the event loop never waits on the disk): `target` is a SQLite path or a
`postgresql://user@host:port/db` URL (psycopg 3). `Repository` has the typed queries,
`records` the typed rows. It stores and loads records only: turning rooms into records and
back is the rooms' job.

The API (each `Repository` method is one transaction, run through the `Database`):

    db = Database(path_or_url, write_retry=600.0, batch=None, start_retry=30.0)
        # connects and migrates, trying again through passing failures for start_retry s
        # batch: queued writes per transaction (default 64 on PostgreSQL, 1 on SQLite)
    db.write(lambda repo: repo.save_room(room_id, text, epoch=e), "save room") -> Future
    db.submit(fn, retry_for=10.0) -> Future   db.run(fn) -> T
    await db.call(fn) -> T    # StoreUnavailable after read_deadline (10 s) or when unreachable
    await db.call(fn, wait=True) -> T          # no deadline (a drain's flush)
    db.close()                                # every queued write done first

    repo.claim_room(room_id, epoch, owner="") -> None
        # StaleOwner if a higher epoch is stored, or the same one by another owner
    repo.room_epoch(room_id) -> int | None
    repo.prune_room_owners(before) -> int   # owners of rooms gone, claimed before `before`
    repo.reserve_match_ids(count) -> range                   # unique across processes
    repo.last_match_id() -> int
    repo.start_match(match_id, room_id, kind, players, race_to, started_at=None, *, epoch=None)
    repo.update_score(match_id, score, *, epoch=None)
    repo.finish_match(match_id, score, winner, reason, status="finished",
                      finished_at=None, *, epoch=None)       # closes once
    repo.record_game(match_id, n, winner, reason, cause, score, finished_at=None,
                     *, epoch=None)                         # a repeat is ignored
    repo.record_shot(match_id, room_shot, game, seat, shot, table, balls, outcome,
                     played_at=None, engine=None, motion=None, *, epoch=None) -> int
        # the shot's n; a repeat of (match_id, room_shot) changes nothing, returns its n
    repo.save_room(room_id, snapshot_json, *, epoch=None)
    repo.delete_room(room_id, *, epoch=None)
    repo.room(room_id) -> RoomSnapshot | None    repo.rooms() -> list[RoomSnapshot]
    repo.match(id)  repo.recent_matches(limit, status, room_id)  repo.games(id)  repo.shots(id)
    repo.shot(id, n)
    with repo.transaction(): ...                 # several calls as one transaction

Fencing: `claim_room` stores the owner's epoch (from the Redis lease) unless a higher one is
stored, or the same one by another owner (then `StaleOwner`). A room-scoped write given
`epoch=` locks the room's owner row (`SELECT ... FOR UPDATE` on PostgreSQL, the write lock
on SQLite) and, when a higher epoch is stored, raises `StaleOwner` and changes nothing; a
room never claimed is claimed by it.
Writes that are retried (passing failures) or replayed (a failover) are idempotent.
"""

from .database import Database
from .errors import StaleOwner, StoreUnavailable
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
    "StaleOwner",
    "StoreUnavailable",
]
