"""Every bound a client must respect, in one place: the server validates against these and
sends them in `welcome`, `GET /api/limits` and the match detail, so no client keeps a copy.
"""

from __future__ import annotations

from pydantic import BaseModel

from server.engine import MAX_ELEVATION, MAX_SPEED, MAX_TIP
from server.engine.shot import DEFAULT_CUE_MASS_RATIO

PROTOCOL_VERSION = 1
MAX_ANGLE = 10.0  # radians; any direction fits in [-pi, pi], this only bounds junk
MAX_CHAT = 200  # characters of one chat line
MAX_NAME = 24  # characters of a player's name
# Frames a `frame` message carried when shots were streamed frame by frame. A shot's
# motion now goes whole at the strike; `welcome` and a match's `stream` still carry the
# old value for clients that read it.
FRAMES_PER_MESSAGE = 4


class Limits(BaseModel):
    """What a client needs to build valid messages."""

    max_speed: float = MAX_SPEED  # m/s of the cue ball
    max_tip: float = MAX_TIP  # tip offset, a fraction of the radius (level cue; see miscue)
    max_elevation: float = MAX_ELEVATION  # the cue's angle above the bed, radians
    max_angle: float = MAX_ANGLE
    max_name: int = MAX_NAME
    max_chat: int = MAX_CHAT
    # Ball mass over the cue's end mass: how far side spin squirts the cue ball off the aim
    # line, so the guide line shows the path the ball will really take.
    cue_mass_ratio: float = DEFAULT_CUE_MASS_RATIO


class StreamRates(BaseModel):
    """How a shot is streamed: the engine's tick rate and which ticks are sent."""

    tick_hz: int
    frame_every: int
    frames_per_message: int


LIMITS = Limits()
