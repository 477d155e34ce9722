"""Which physics played a shot.

A stored shot records the engine version that simulated it. A replay by an engine of
another version would give another result without any error, so a caller compares versions
before it re-simulates instead of trusting a silent difference.

The version is `"<revision>+<digest>"`: `PHYSICS_REVISION` is bumped by hand when the code
of the physics changes what a shot does; the digest covers every number that does (the
physics parameters, the tick, the table and rack constants and the kernels' thresholds), so
changing one of those changes the version by itself.
"""

from __future__ import annotations

import hashlib
from dataclasses import fields

from .params import DEFAULT_PARAMS, PhysicsParams
from .physics import constants
from .rack import JITTER, LATTICE_GAP
from .simulate import DEFAULT_TICK, MAX_SHOT_SECONDS
from .table import (
    BALL_MASS,
    BALL_RADIUS,
    CORNER_FACING_DEG,
    CORNER_HOLE,
    CORNER_MOUTH,
    CORNER_SHELF,
    SIDE_FACING_DEG,
    SIDE_HOLE,
    SIDE_MOUTH,
    SIDE_SHELF,
    TABLE_SIZES,
)

# Bump when a change to the physics code changes a result without changing a number below.
# 2: Han 2005 cushion above the centre, throw and spin transfer, squirt, pockets with
#    facings, shelf and hole (issue 14).
PHYSICS_REVISION = 2

# Module constants that change a result, by name.
_CONSTANTS: tuple[tuple[str, int | float], ...] = (
    ("table.BALL_RADIUS", BALL_RADIUS),
    ("table.BALL_MASS", BALL_MASS),
    ("table.CORNER_MOUTH", CORNER_MOUTH),
    ("table.SIDE_MOUTH", SIDE_MOUTH),
    ("table.CORNER_FACING_DEG", CORNER_FACING_DEG),
    ("table.SIDE_FACING_DEG", SIDE_FACING_DEG),
    ("table.CORNER_SHELF", CORNER_SHELF),
    ("table.SIDE_SHELF", SIDE_SHELF),
    ("table.CORNER_HOLE", CORNER_HOLE),
    ("table.SIDE_HOLE", SIDE_HOLE),
    ("rack.LATTICE_GAP", LATTICE_GAP),
    ("rack.JITTER", JITTER),
    ("constants.EPS_SPEED", constants.EPS_SPEED),
    ("constants.EPS_SPIN", constants.EPS_SPIN),
    ("constants.MAX_EVENTS_PER_TICK", constants.MAX_EVENTS_PER_TICK),
    ("simulate.MAX_SHOT_SECONDS", MAX_SHOT_SECONDS),
    *(
        (f"table.TABLE_SIZES[{size}][{k}]", value)
        for size in sorted(TABLE_SIZES)
        for k, value in enumerate(TABLE_SIZES[size])
    ),
)


def _exact(value: int | float) -> str:
    """Exact text of a number: integers as written, floats by `float.hex`."""
    return str(value) if isinstance(value, int) else float(value).hex()


def engine_version(
    params: PhysicsParams = DEFAULT_PARAMS,
    tick: float = DEFAULT_TICK,
    revision: int = PHYSICS_REVISION,
) -> str:
    """The version of an engine run with `params` and `tick`: `"<revision>+<12 hex>"`.

    Parameters are hashed as the float64 values the kernels receive, so `g=10` and
    `g=10.0` are the same engine.
    """
    lines = [f"revision={revision}", f"tick={float(tick).hex()}"]
    lines += [f"params.{f.name}={float(getattr(params, f.name)).hex()}" for f in fields(params)]
    lines += [f"{name}={_exact(value)}" for name, value in _CONSTANTS]
    digest = hashlib.sha256("\n".join(lines).encode()).hexdigest()[:12]
    return f"{revision}+{digest}"


ENGINE_VERSION = engine_version()
