"""A live room as saved data and back: seats (token hashes only), the match, the shot in
flight.

Saved after every shot and every change at rest. While a shot is being streamed the saved
room is the one from *before* the shot plus `pending` (the shot itself): after a restart
the shot is played again from that start state, which gives the same result bit for bit.
The saved form is a dataclass turned into JSON by `server.codec`, the same mechanism as
every other stored type.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Literal

from server.codec import from_data, to_data, to_json
from server.engine import Shot
from server.rules import Match
from server.store import PendingShot

from .drills import DrillScore, DrillSetup, DrillTries
from .room import Room, Seat


@dataclass(frozen=True)
class SavedSeat:
    name: str
    token_hash: str


@dataclass(frozen=True)
class SavedRoomData:
    """The stored form (version 1)."""

    version: Literal[1]
    room_id: str
    game: str
    race_to: int
    shot_clock: float
    seed: int
    created_at: float
    seats: list[SavedSeat | None]
    match: dict[str, Any] | None  # Match.to_dict()
    match_id: int | None
    shots_played: int
    rematch_votes: list[int]
    pending: PendingShot | None
    listed: bool = True
    computer: dict[int, str] = field(default_factory=dict)  # seat -> level
    shots_by_seat: list[int] | None = None  # None: saved before it was kept
    setup: DrillSetup | None = None  # a drill's table (rooms/drills.py)
    drill: DrillScore | None = None  # and how it went so far
    tries: DrillTries | None = None  # the drill's tries in the room (None: one)


@dataclass(frozen=True)
class SavedRoom:
    """A restored room (every seat disconnected), its match record and the shot to replay."""

    room: Room
    match_id: int | None
    pending: tuple[int, Shot] | None  # (seat, shot)
    pending_id: int | None = None


def room_to_snapshot(
    room: Room, match_id: int | None, pending: PendingShot | None = None
) -> dict[str, Any]:
    """The room at rest (or just before `pending` was struck), as plain data."""
    result: dict[str, Any] = to_data(_saved(room, match_id, pending))
    return result


def room_snapshot_json(room: Room, match_id: int | None, pending: PendingShot | None = None) -> str:
    """`room_to_snapshot` as JSON text in one pass (pydantic's serializer, ~2.5x faster
    than plain data then `json.dumps`: the server saves a room twice a shot)."""
    return to_json(_saved(room, match_id, pending))


def _saved(room: Room, match_id: int | None, pending: PendingShot | None) -> SavedRoomData:
    shots_played = room.shots_played if pending is None else pending.id - 1
    by_seat = list(room.shots_by_seat)
    if pending is not None:  # saved as just before it was struck
        by_seat[pending.seat] -= 1
    return SavedRoomData(
        version=1,
        room_id=room.room_id,
        game=room.game,
        race_to=room.race_to,
        shot_clock=room.shot_clock,
        seed=room.seed,
        created_at=room.created_at,
        seats=[None if s is None else SavedSeat(s.name, s.token_hash) for s in room.seats],
        match=room.match.to_dict() if room.match is not None else None,
        match_id=match_id,
        shots_played=shots_played,
        rematch_votes=sorted(room.rematch_votes),
        pending=pending,
        listed=room.listed,
        computer=dict(room.computer),
        shots_by_seat=by_seat,
        setup=room.setup,
        drill=room.drill if room.setup is not None else None,
        tries=room.tries if room.setup is not None else None,
    )


def room_from_snapshot(data: dict[str, Any]) -> SavedRoom:
    """The inverse of `room_to_snapshot`; raises ValueError on data it cannot read."""
    if data.get("version") != 1:
        raise ValueError(f"unknown room snapshot version {data.get('version')!r}")
    saved = from_data(SavedRoomData, data)
    room = Room(
        saved.room_id,
        saved.game,
        race_to=saved.race_to,
        shot_clock=saved.shot_clock,
        seed=saved.seed,
        created_at=saved.created_at,
        listed=saved.listed,
        setup=saved.setup,
    )
    room.seats = [None if s is None else Seat(s.name, s.token_hash) for s in saved.seats]
    room.computer = dict(saved.computer)
    room.drill = saved.drill or DrillScore()
    room.tries = saved.tries or DrillTries()
    for seat in room.computer:  # the computer never leaves
        seat_info = room.seats[seat]
        if seat_info is not None:
            seat_info.connected = True
    room.match = Match.from_dict(saved.match) if saved.match is not None else None
    room.shots_played = saved.shots_played
    # A room saved before the count was kept: every seat counted as having played once a
    # shot was (the rule it was saved under).
    by_seat = saved.shots_by_seat
    room.shots_by_seat = list(by_seat) if by_seat else [saved.shots_played] * len(room.seats)
    room.rematch_votes = set(saved.rematch_votes)
    p = saved.pending
    pending = None if p is None else (p.seat, Shot(p.angle, p.speed, p.tip, p.elevation))
    return SavedRoom(room, saved.match_id, pending, None if p is None else p.id)


def pending_shot(shot_id: int, seat: int, shot: Shot) -> PendingShot:
    tip = (shot.tip[0], shot.tip[1])
    return PendingShot(shot_id, seat, shot.angle, shot.speed, tip, shot.elevation)
