"""Rooms: seats and tokens, the room state machine, shot streaming, live connections.

`room` is the synchronous state machine (no I/O); `live` drives it with clocks and the shot
stream; `connection` is one client's bounded outbox; `registry` holds the rooms.
"""

from .errors import ActionError
from .registry import RoomRegistry
from .room import Room

__all__ = ["ActionError", "Room", "RoomRegistry"]
