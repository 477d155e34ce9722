"""Pure pool physics: table geometry, balls, racks, shots and the fixed-tick event engine.

No I/O, no asyncio: the server, the rules, the tests and the benchmarks all drive it alone.
A shot can be traced for drawing (`ShotInMotion.run(trace=...)`, `simulate_traced`: per
ball, the knots of its exact motion) in the same compiled call that simulates it.
"""

from .balls import CUE, BallSet, MotionState
from .params import DEFAULT_PARAMS, PhysicsParams
from .physics.constants import OFF_TABLE
from .rack import rack, rack_slots
from .results import Event, EventKind, FlightKind, Frame, FrameSequence, Settled, ShotResult
from .shot import (
    MAX_ELEVATION,
    MAX_SPEED,
    MAX_TIP,
    Miscue,
    Shot,
    check_stroke,
    cue_offset,
    tip_seen_level,
)
from .simulate import (
    DEFAULT_TICK,
    TICK_HZ,
    ShotInMotion,
    run_to_rest,
    settle,
    simulate,
    simulate_traced,
    step,
    strike,
)
from .table import BALL_MASS, BALL_RADIUS, Cushion, Pocket, Table
from .tracing import Tolerance, Trace
from .version import ENGINE_VERSION, PHYSICS_REVISION, engine_version

__all__ = [
    "BALL_MASS",
    "BALL_RADIUS",
    "CUE",
    "DEFAULT_PARAMS",
    "DEFAULT_TICK",
    "ENGINE_VERSION",
    "MAX_ELEVATION",
    "MAX_SPEED",
    "MAX_TIP",
    "OFF_TABLE",
    "PHYSICS_REVISION",
    "TICK_HZ",
    "BallSet",
    "Cushion",
    "Event",
    "EventKind",
    "FlightKind",
    "Frame",
    "FrameSequence",
    "Miscue",
    "MotionState",
    "PhysicsParams",
    "Pocket",
    "Settled",
    "Shot",
    "ShotInMotion",
    "ShotResult",
    "Table",
    "Tolerance",
    "Trace",
    "check_stroke",
    "cue_offset",
    "engine_version",
    "rack",
    "rack_slots",
    "run_to_rest",
    "settle",
    "simulate",
    "simulate_traced",
    "step",
    "strike",
    "tip_seen_level",
]
