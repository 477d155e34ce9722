"""The balls on a table: state per ball kept in parallel numpy arrays.

Ball ids are 0 (the cue ball) to 21: pool uses 0-15 (9-ball 0-9), snooker 0-21 (`rack`).
A `BallSet` may hold any subset; row `i` of every array belongs to ball `ids[i]`.

Its stored form is the codec's (`server.codec.to_data`): one nested list per array, floats
exact, so a stored table replays bit for bit.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from enum import IntEnum
from typing import TYPE_CHECKING, Annotated, Any

import numpy as np
from pydantic import Field

from ..codec import from_data, to_dict
from .params import DEFAULT_PARAMS, PhysicsParams
from .physics.constants import AIRBORNE, OFF_TABLE, POCKETED, ROLLING, SLIDING
from .physics.tick import cels_of

if TYPE_CHECKING:  # to mypy the codec's array types are values; pydantic reads the real ones
    Float64Array = np.ndarray
    Int64Array = np.ndarray
else:
    from ..codec import Float64Array, Int64Array

CUE = 0
MAX_BALL_ID = 21  # snooker: the cue ball, 15 reds and six colours

# Each array's shape after the ball count.
_SHAPES = (
    ("ids", ()),
    ("positions", (2,)),
    ("velocities", (2,)),
    ("spins", (3,)),
    ("states", ()),
    ("phases", ()),
    ("pockets", ()),
    ("heights", (2,)),
)


def _flat(heights: np.ndarray) -> bool:
    """Every ball on the bed: the stored form leaves `heights` out, as before it existed."""
    return not heights.any()


class MotionState(IntEnum):
    """What a ball is doing; decides which friction law moves it. The kernels' plain ints
    (`physics.constants`) are the same values; array code compares with those, since
    numpy compares an array with an IntEnum member (an int subclass) about 4 times slower
    than with an int, and the search does it thousands of times a turn."""

    STATIONARY = 0
    SPINNING = 1  # in place, about the vertical axis only
    SLIDING = 2  # the contact point slips on the cloth
    ROLLING = 3  # no slip
    POCKETED = 4  # out of play: in a pocket, or off the table (its pocket OFF_TABLE)
    AIRBORNE = 5  # in flight after a jump or a hop (`heights`)


@dataclass
class BallSet:
    """Mutable ball state. The engine's `step` advances it in place; `copy()` before keeping.

    positions (N, 2) m; velocities (N, 2) m/s; spins (N, 3) rad/s (angular velocity, z up);
    states (N,) MotionState; phases (N,) rad rolled (drives the sprite cel);
    pockets (N,) pocket index for a pocketed ball, OFF_TABLE (-2) for a ball that flew off
    the table, else -1; heights (N, 2): the centre's height above its resting height (m)
    and vertical speed (m/s), both 0 on the bed (a stored set without them is on the bed).
    """

    ids: Int64Array
    positions: Float64Array
    velocities: Float64Array
    spins: Float64Array
    states: Int64Array
    phases: Float64Array
    pockets: Int64Array
    heights: Annotated[Float64Array, Field(exclude_if=_flat)] = None  # type: ignore[assignment]

    def __post_init__(self) -> None:
        """Refuse arrays that disagree on the ball count: loaded data is checked here, and
        an empty set's arrays take their 2-D shapes back from flat empty lists."""
        n = len(self.ids)
        if self.heights is None:
            self.heights = np.zeros((n, 2))
        for name, tail in _SHAPES:
            shape = (n, *tail)
            array = getattr(self, name)
            if array.shape != shape:
                if array.size != 0 or n != 0:
                    raise ValueError(f"{name} has shape {array.shape}, expected {shape}")
                setattr(self, name, array.reshape(shape))

    @classmethod
    def place(cls, placement: Mapping[int, tuple[float, float]]) -> BallSet:
        """Stationary balls at the given centres, ordered by id."""
        if not placement:
            raise ValueError("place needs at least one ball")
        ids = sorted(placement)
        if len(set(ids)) != len(ids) or ids[0] < 0 or ids[-1] > MAX_BALL_ID:
            raise ValueError(f"ball ids must be distinct and within 0..{MAX_BALL_ID}")
        n = len(ids)
        positions = np.array([placement[i] for i in ids], dtype=np.float64).reshape(n, 2)
        if not np.all(np.isfinite(positions)):
            raise ValueError("ball positions must be finite")
        return cls(
            ids=np.array(ids, dtype=np.int64),
            positions=positions,
            velocities=np.zeros((n, 2)),
            spins=np.zeros((n, 3)),
            states=np.full(n, MotionState.STATIONARY, dtype=np.int64),
            phases=np.zeros(n),
            pockets=np.full(n, -1, dtype=np.int64),
            heights=np.zeros((n, 2)),
        )

    @classmethod
    def of_arrays(
        cls,
        ids: np.ndarray,
        positions: np.ndarray,
        velocities: np.ndarray,
        spins: np.ndarray,
        states: np.ndarray,
        phases: np.ndarray,
        pockets: np.ndarray,
        heights: np.ndarray,
    ) -> BallSet:
        """A set holding these arrays as they are, unchecked: for arrays the engine made
        from a checked set (the shapes are that set's), where checking them again only
        costs time (a search makes thousands of sets a turn)."""
        out = object.__new__(cls)
        out.ids = ids
        out.positions = positions
        out.velocities = velocities
        out.spins = spins
        out.states = states
        out.phases = phases
        out.pockets = pockets
        out.heights = heights
        return out

    def copy(self) -> BallSet:
        """A copy sharing no array (its shapes are this set's, checked already)."""
        return BallSet.of_arrays(
            self.ids.copy(),
            self.positions.copy(),
            self.velocities.copy(),
            self.spins.copy(),
            self.states.copy(),
            self.phases.copy(),
            self.pockets.copy(),
            self.heights.copy(),
        )

    def __len__(self) -> int:
        return len(self.ids)

    def index(self, ball_id: int) -> int:
        """Row of ball `ball_id`; KeyError when the set does not hold it."""
        try:  # a list's index: a few times quicker than numpy's on a rack's 16 ids
            row: int = self.ids.tolist().index(ball_id)
            return row
        except ValueError:
            raise KeyError(ball_id) from None

    @property
    def on_table(self) -> np.ndarray:
        """(N,) bool: the ball has not been pocketed."""
        on: np.ndarray = self.states != POCKETED
        return on

    @property
    def moving(self) -> np.ndarray:
        """(N,) bool: the ball translates (sliding, rolling or in flight)."""
        states = self.states
        moving: np.ndarray = (states == SLIDING) | (states == ROLLING) | (states == AIRBORNE)
        return moving

    @property
    def off_table(self) -> np.ndarray:
        """(N,) bool: the ball flew off the table (out of play, in no pocket)."""
        off: np.ndarray = (self.states == POCKETED) & (self.pockets == OFF_TABLE)
        return off

    def off_table_ids(self) -> list[int]:
        ids: list[int] = self.ids[self.off_table].tolist()
        return ids

    def at_rest(self) -> bool:
        """No ball translates any more."""
        return not bool(self.moving.any())

    def cels(self, params: PhysicsParams = DEFAULT_PARAMS) -> np.ndarray:
        """(N,) int: the sprite cel each ball shows, from the angle it has rolled, by the
        kernel that numbers a shot's frames: a table at rest, a re-spotted ball and a
        stored table all show the cel their roll gives."""
        out = np.empty(len(self), dtype=np.int64)
        cels_of(self.phases, out, params.array())
        return out

    def position_of(self, ball_id: int) -> tuple[float, float]:
        x, y = self.positions[self.index(ball_id)]
        return (float(x), float(y))

    def pocketed_ids(self) -> list[int]:
        ids: list[int] = self.ids[~self.on_table].tolist()
        return ids

    def on_table_ids(self) -> list[int]:
        ids: list[int] = self.ids[self.on_table].tolist()
        return ids

    def with_ball(self, ball_id: int, xy: tuple[float, float]) -> BallSet:
        """A copy with ball `ball_id` stationary on the table at `xy` (spotting, ball in hand)."""
        out = self.copy()
        row = out.index(ball_id)
        out.positions[row] = xy
        out.velocities[row] = 0.0
        out.spins[row] = 0.0
        out.states[row] = MotionState.STATIONARY
        out.pockets[row] = -1
        out.heights[row] = 0.0
        return out

    def with_only(self, placement: Mapping[int, tuple[float, float]]) -> BallSet:
        """A copy with exactly the balls of `placement` at rest on the table there and every
        other ball pocketed (in pocket 0): a crafted position for a test or a benchmark."""
        out = self.copy()
        for ball in out.ids.tolist():
            if ball in placement:
                out = out.with_ball(ball, placement[ball])
            else:
                row = out.index(ball)
                out.states[row] = MotionState.POCKETED
                out.pockets[row] = 0
        return out

    def kinetic_energy(self, mass: float, radius: float) -> float:
        """Translational (the vertical speed of a flying ball too) plus rotational kinetic
        energy of the balls on the table (J)."""
        on = self.on_table
        inertia = 0.4 * mass * radius * radius
        return float(
            0.5 * mass * (np.sum(self.velocities[on] ** 2) + np.sum(self.heights[on, 1] ** 2))
            + 0.5 * inertia * np.sum(self.spins[on] ** 2)
        )

    def mechanical_energy(self, mass: float, radius: float, g: float) -> float:
        """`kinetic_energy` plus the height's potential energy m g z (J): what never rises
        while a ball flies."""
        on = self.on_table
        return self.kinetic_energy(mass, radius) + float(mass * g * np.sum(self.heights[on, 0]))

    def to_dict(self) -> dict[str, Any]:
        """The stored form: `server.codec.to_data(self)`."""
        return to_dict(self)

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> BallSet:
        """The inverse of `to_dict`: `server.codec.from_data(BallSet, data)`."""
        return from_data(cls, dict(data))
