"""The wire protocol, shared by the live rooms and the HTTP API: every message model (in
and out), the one encoder, and a shot's motion: packed (the engine traces it) and planned.

It sits below `rooms` and `api` and imports only the engine (for its limits and results).
"""

from .inbound import AnyClientMessage, BadMessage, parse_client_message
from .limits import LIMITS, PROTOCOL_VERSION, Limits, StreamRates
from .motion import Tracks, run_traced, trace
from .plan import BallRow, ShotPlan, StreamFrames, Timed, frame_rows, plan_shot

__all__ = [
    "LIMITS",
    "PROTOCOL_VERSION",
    "AnyClientMessage",
    "BadMessage",
    "BallRow",
    "Limits",
    "ShotPlan",
    "StreamFrames",
    "StreamRates",
    "Timed",
    "Tracks",
    "frame_rows",
    "parse_client_message",
    "plan_shot",
    "run_traced",
    "trace",
]
