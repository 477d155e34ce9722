"""Rooms: seats and tokens, the room state machine, shot streaming, live connections.

`room` is the synchronous state machine (no I/O); `live` drives it on the event loop,
through its parts: `stream` (what members are sent), `timers` (shot clock and reconnection
grace), `shots` (a shot simulated and shown), `computer_turns` and `chat`. `connection` is
one client's bounded outbox; `registry` holds the rooms and brings saved ones back;
`recorder` and `snapshot` turn rooms into the store's records.
"""

from .clock import SYSTEM_CLOCK, Clock, SeedSource
from .errors import ActionError
from .live import LiveRoom
from .recorder import StoreObserver
from .registry import RoomRegistry
from .room import Room

__all__ = [
    "SYSTEM_CLOCK",
    "ActionError",
    "Clock",
    "LiveRoom",
    "Room",
    "RoomRegistry",
    "SeedSource",
    "StoreObserver",
]
