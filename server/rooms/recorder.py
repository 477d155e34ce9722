"""`StoreObserver`: the room observer that records matches, games and shots and saves rooms.

It runs on the event loop, so it only builds the rows (plain data, copied from the room at
that instant) and queues them on the store's thread; nothing here waits for the disk. Each
shot is stored with the engine version that played it and the motion that was streamed, so
a replay shows what was played even after the physics changes.
"""

from __future__ import annotations

import asyncio
import itertools
from collections.abc import Callable, Iterator
from concurrent.futures import Future
from dataclasses import dataclass
from typing import Any

from server.codec import to_data
from server.engine import ENGINE_VERSION, BallSet, Shot
from server.protocol import ShotPlan
from server.protocol.plan import motion_text
from server.rules import Outcome
from server.store import Database, Repository, StaleOwner
from server.store.drills import DrillRows

from .room import Room
from .snapshot import pending_shot, room_snapshot_json


@dataclass
class _Tracked:
    match_id: int
    finished: bool = False
    shots: int = 0  # shots played in this match (a match decided without one was abandoned)


class StoreObserver:
    """Implements `server.rooms.observer.RoomObserver` over a `Database`."""

    def __init__(self, db: Database) -> None:
        self.db = db
        self._ids: Iterator[int] = itertools.count(db.run(lambda repo: repo.last_match_id()) + 1)
        self._epoch_of: Callable[[str], int | None] = lambda _room_id: None
        self._stale: Callable[[str], None] = lambda _room_id: None
        self._matches: dict[str, _Tracked] = {}
        self.active = True  # False once the server shuts down: rooms are kept, not deleted

    def room_restored(self, room: Room, match_id: int | None) -> None:
        """A room restored after a restart keeps its match record."""
        if match_id is not None and room.match is not None:
            over = room.match.over or room.abandoned
            self._matches[room.room_id] = _Tracked(match_id, over, room.shots_played)

    def room_unreadable(self, room_id: str) -> None:
        """A saved room that cannot be restored is dropped, so it is not retried forever."""
        self.db.write(lambda repo: repo.delete_room(room_id), "drop room")

    def start(self) -> None:
        """Record again (a new lifespan of the same app)."""
        self.active = True

    def stop(self) -> None:
        """The server is going down: stop recording; the saved rooms stay for the restart."""
        self.active = False

    def use_cluster(
        self,
        ids: Iterator[int],
        epoch_of: Callable[[str], int | None],
        stale: Callable[[str], None],
    ) -> None:
        """Cluster mode: match ids from `ids` (unique across the processes sharing the
        store); `epoch_of(room_id)` is the fencing epoch this process owns a room under,
        and `stale(room_id)` is told when the store refuses a write for it."""
        self._ids = ids
        self._epoch_of = epoch_of
        self._stale = stale

    def match_id(self, room: Room) -> int | None:
        """The record of the room's current match, started when the match starts (and again
        on a rematch)."""
        match = room.match
        if match is None:
            return None
        tracked = self._matches.get(room.room_id)
        if tracked is None or (tracked.finished and not match.over and not room.abandoned):
            tracked = _Tracked(next(self._ids))
            self._matches[room.room_id] = tracked
            args = (tracked.match_id, room.room_id, match.kind, list(match.players), match.race_to)
            self._write(
                room.room_id, lambda repo, e: repo.start_match(*args, epoch=e), "start match"
            )
        return tracked.match_id

    # ---- RoomObserver -----------------------------------------------------------------

    def shot_started(self, room: Room, seat: int, shot: Shot, shot_id: int) -> Future[Any] | None:
        """Save the room as it was before the shot, with the shot: a restart, or the next
        owner, replays it. The returned future is done once it is stored (and every write
        queued before it: the shots before this one): the motion waits for it."""
        if not self.active:
            return None
        match_id = self.match_id(room)
        text = room_snapshot_json(room, match_id, pending_shot(shot_id, seat, shot))
        return self._write(
            room.room_id, lambda repo, e: repo.save_room(room.room_id, text, epoch=e), "save room"
        )

    def shot_played(
        self, room: Room, seat: int, shot: Shot, before: BallSet, outcome: Outcome, plan: ShotPlan
    ) -> None:
        if not self.active or room.match is None:
            return
        match = room.match
        match_id = self.match_id(room)
        assert match_id is not None and room.shot is not None
        scored = outcome.frame_over and outcome.winner is not None
        game_no = match.games_played + (0 if scored else 1)
        row = (
            match_id,
            room.shot.id,
            game_no,
            seat,
            to_data(shot),
            match.game.table.fields(),
            before.to_dict(),
            outcome.to_dict(),
        )
        engine, motion = ENGINE_VERSION, motion_text(plan)
        meant = room.shot.intended
        intended = None if meant is None or meant == shot else to_data(meant)
        self._matches[room.room_id].shots += 1
        self._write(
            room.room_id,
            lambda repo, e: repo.record_shot(
                *row, engine=engine, motion=motion, intended=intended, epoch=e
            ),
            "record shot",
        )
        if room.setup is not None:  # a drill: how it went, for the personal bests
            d, t = room.drill, room.tries
            tried = (room.room_id, t.best, d.done, t.cleared > 0, t.tries, t.cleared)
            self._write(
                room.room_id, lambda repo, _e: DrillRows(repo).set_score(*tried), "drill score"
            )
        self._scored(room, "shot", outcome)

    def outcome(self, room: Room, cause: str, outcome: Outcome) -> None:
        if self.active:
            self._scored(room, cause, outcome)

    def room_changed(self, room: Room) -> None:
        if not self.active:
            return
        match_id = self.match_id(room)
        self._finish_if_over(room)
        text = room_snapshot_json(room, match_id)
        self._write(
            room.room_id, lambda repo, e: repo.save_room(room.room_id, text, epoch=e), "save room"
        )

    def room_closed(self, room: Room) -> None:
        """The room expired: forget it; a match left unfinished is marked abandoned."""
        if not self.active:
            return
        tracked = self._matches.pop(room.room_id, None)
        room_id = room.room_id
        self._write(room_id, lambda repo, e: repo.delete_room(room_id, epoch=e), "delete room")
        if tracked is not None and not tracked.finished and room.match is not None:
            score = list(room.match.score)
            self._write(
                room_id,
                lambda repo, e: repo.finish_match(
                    tracked.match_id,
                    score,
                    None,
                    "The room closed before the end.",
                    status="abandoned",
                    epoch=e,
                ),
                "abandon match",
            )

    # ---- helpers ----------------------------------------------------------------------

    def _write(
        self, room_id: str, fn: Callable[[Repository, int | None], object], what: str
    ) -> Future[Any]:
        """Queue a write about `room_id` carrying the epoch this process owns it under
        (cluster mode; None otherwise); returns its future. A refusal (`StaleOwner`:
        another process owns the room now) is reported to `stale` on the event loop."""
        epoch = self._epoch_of(room_id)
        future: Future[Any] = self.db.write(lambda repo: fn(repo, epoch), what)
        if epoch is None:
            return future
        loop = asyncio.get_running_loop()

        def done(f: Future[Any]) -> None:
            if isinstance(f.exception(), StaleOwner):
                loop.call_soon_threadsafe(self._stale, room_id)

        future.add_done_callback(done)
        return future

    def _scored(self, room: Room, cause: str, outcome: Outcome) -> None:
        match = room.match
        match_id = self.match_id(room)
        if match is None or match_id is None:
            return
        if outcome.frame_over and outcome.winner is not None:
            args = (
                match_id,
                match.games_played,
                outcome.winner,
                outcome.reason,
                cause,
                list(match.score),
            )
            self._write(
                room.room_id, lambda repo, e: repo.record_game(*args, epoch=e), "record game"
            )
        self._finish_if_over(room)

    def _finish_if_over(self, room: Room) -> None:
        """Record the end of the match: finished with its winner, or abandoned when every
        player left, or when it was decided without a single shot (frames forfeited by a
        player who never played): nobody won such a match and there is nothing to watch."""
        match = room.match
        tracked = self._matches.get(room.room_id)
        if match is None or tracked is None or tracked.finished:
            return
        if room.abandoned:
            reason = "Both players left the table."
        elif not match.over:
            return
        elif tracked.shots == 0:
            reason = match.reason or "Nobody played a shot."
        else:
            tracked.finished = True
            args = (tracked.match_id, list(match.score), match.winner, match.reason)
            self._write(
                room.room_id, lambda repo, e: repo.finish_match(*args, epoch=e), "finish match"
            )
            return
        tracked.finished = True
        abandoned = (tracked.match_id, list(match.score), None, reason)
        self._write(
            room.room_id,
            lambda repo, e: repo.finish_match(*abandoned, status="abandoned", epoch=e),
            "abandon match",
        )
