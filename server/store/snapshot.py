"""A live room as JSON and back: seats (token hashes only), the match, the shot in flight.

Saved after every shot and every change at rest. While a shot is being streamed the saved
room is the one from *before* the shot plus `pending` (the shot itself): after a restart
the shot is played again from that start state, which gives the same result bit for bit.
"""

from __future__ import annotations

import json

from server.engine import Shot
from server.rooms.room import Room, Seat
from server.rules import Match

from .records import PendingShot

VERSION = 1


def room_to_dict(room: Room, match_id: int | None, pending: PendingShot | None = None) -> dict:
    """The room at rest (or just before `pending` was struck)."""
    shots_played = room.shots_played if pending is None else pending.id - 1
    return {
        "version": VERSION,
        "room_id": room.room_id, "game": room.game, "race_to": room.race_to,
        "shot_clock": room.shot_clock, "seed": room.seed, "created_at": room.created_at,
        "seats": [None if s is None else {"name": s.name, "token_hash": s.token_hash}
                  for s in room.seats],
        "match": room.match.to_dict() if room.match is not None else None,
        "match_id": match_id,
        "shots_played": shots_played,
        "rematch_votes": sorted(room.rematch_votes),
        "pending": None if pending is None else {
            "id": pending.id, "seat": pending.seat, "angle": pending.angle,
            "speed": pending.speed, "tip": list(pending.tip)},
    }


def room_to_json(room: Room, match_id: int | None, pending: PendingShot | None = None) -> str:
    return json.dumps(room_to_dict(room, match_id, pending), separators=(",", ":"),
                      allow_nan=False)


def room_from_dict(data: dict) -> tuple[Room, int | None, PendingShot | None]:
    """The room (every seat disconnected), its match record id and the shot to replay."""
    if data.get("version") != VERSION:
        raise ValueError(f"unknown room snapshot version {data.get('version')!r}")
    room = Room(data["room_id"], data["game"], race_to=data["race_to"],
                shot_clock=data["shot_clock"], seed=data["seed"],
                created_at=data["created_at"])
    room.seats = [None if s is None else Seat(s["name"], s["token_hash"])
                  for s in data["seats"]]
    room.match = Match.from_dict(data["match"]) if data["match"] is not None else None
    room.shots_played = data["shots_played"]
    room.rematch_votes = set(data["rematch_votes"])
    p = data["pending"]
    pending = None if p is None else PendingShot(p["id"], p["seat"], p["angle"], p["speed"],
                                                 (p["tip"][0], p["tip"][1]))
    return room, data["match_id"], pending


def pending_shot(shot_id: int, seat: int, shot: Shot) -> PendingShot:
    return PendingShot(shot_id, seat, shot.angle, shot.speed, (shot.tip[0], shot.tip[1]))
