"""Bring the saved rooms back after a restart (called from the app's lifespan)."""

from __future__ import annotations

import logging

from server.config import Settings
from server.engine import Shot
from server.rooms import RoomRegistry
from server.rooms.live import LiveRoom

from .database import Database
from .recorder import StoreObserver
from .snapshot import room_from_dict

log = logging.getLogger(__name__)


def restore_rooms(db: Database, registry: RoomRegistry, settings: Settings,
                  observer: StoreObserver) -> list[LiveRoom]:
    """Every saved room, seats empty until their players reconnect with their tokens; a
    shot that was in flight is played again from its start. Needs the running loop."""
    restored = []
    for snap in db.run(lambda repo: repo.rooms()):
        if registry.get(snap.room_id) is not None:
            continue  # still live in this process
        try:
            room, match_id, pending = room_from_dict(snap.data)
        except (KeyError, TypeError, ValueError):
            log.exception("room %s could not be restored; dropped", snap.room_id)
            db.write(lambda repo, rid=snap.room_id: repo.delete_room(rid), "drop room")
            continue
        observer.adopt(room, match_id)
        live = LiveRoom(room, settings, observer)
        registry.add(live)
        shot = None if pending is None else (pending.seat, Shot(pending.angle, pending.speed,
                                                                pending.tip))
        live.resume(shot)
        restored.append(live)
    if restored:
        log.info("restored %d rooms", len(restored))
    return restored
