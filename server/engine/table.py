"""Table geometry: the playing surface, its cushions, the pocket jaws and the pockets.

SI units. The origin is the bottom-left corner of the playing surface measured at the
cushion noses; x runs along the long side. The head (where the break is taken from) is the
left quarter, the rack sits on the foot spot in the right quarter.

A cushion is a straight segment of a rail between two pocket mouths. Its two ends are the
jaws (the "points" of the pocket): points a ball can hit. A ball is pocketed when its centre
crosses the mouth line between the two jaws of a pocket.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field, fields
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from pydantic import GetCoreSchemaHandler
    from pydantic_core import CoreSchema

BALL_RADIUS = 0.028575  # m (2.25 in diameter, WPA)
BALL_MASS = 0.17  # kg

# Playing-surface sizes (length, width) in metres, WPA.
TABLE_SIZES: dict[str, tuple[float, float]] = {
    "9ft": (2.54, 1.27),
    "8ft": (2.34, 1.17),
    "7ft": (1.98, 0.99),
}
CORNER_MOUTH = 0.114  # m, jaw to jaw
SIDE_MOUTH = 0.127  # m, jaw to jaw


@dataclass(frozen=True)
class Cushion:
    """A straight cushion nose from `start` to `end`; `normal` points into the playing area."""

    start: tuple[float, float]
    end: tuple[float, float]
    normal: tuple[float, float]


@dataclass(frozen=True)
class Pocket:
    """A pocket: the mouth between two jaw points, and a drop circle behind it.

    `outward` is the unit normal of the mouth line pointing into the pocket; `center` and
    `radius` describe the hole for drawing and for placing pocketed balls.
    """

    name: str
    jaws: tuple[tuple[float, float], tuple[float, float]]
    outward: tuple[float, float]
    center: tuple[float, float]
    radius: float


@dataclass(frozen=True)
class Table:
    """A pool table: playing-surface size, cushions, jaws and pockets (all derived).

    Stored through the codec (`server.codec.to_data`) as its constructor fields only,
    `{"length", "width", "ball_radius", "corner_mouth", "side_mouth"}`; the geometry is
    rebuilt on load. The codec also loads the older stored form, those fields as a list.
    `to_dict` is not storage: it is the derived geometry browsers draw.
    """

    length: float
    width: float
    ball_radius: float = BALL_RADIUS
    corner_mouth: float = CORNER_MOUTH
    side_mouth: float = SIDE_MOUTH
    cushions: tuple[Cushion, ...] = field(init=False, repr=False)
    pockets: tuple[Pocket, ...] = field(init=False, repr=False)

    @classmethod
    def pool(cls, size: str = "9ft") -> Table:
        """A WPA pool table: "9ft", "8ft" or "7ft"."""
        try:
            length, width = TABLE_SIZES[size]
        except KeyError:
            raise ValueError(
                f"unknown table size {size!r}; choose one of {sorted(TABLE_SIZES)}"
            ) from None
        return cls(length, width)

    @classmethod
    def from_fields(cls, values: Sequence[float]) -> Table:
        """A table from its constructor fields in order: the list form stored before the
        codec (`[length, width, ball_radius, corner_mouth, side_mouth]`)."""
        return cls(*(float(v) for v in values))

    @classmethod
    def __get_pydantic_core_schema__(cls, source: Any, handler: GetCoreSchemaHandler) -> CoreSchema:
        """The codec's schema for the fields, taking the older list form as well."""
        from pydantic_core import core_schema

        return core_schema.no_info_before_validator_function(_fields_by_name, handler(source))

    def __post_init__(self) -> None:
        cushions, pockets = _build_geometry(
            self.length, self.width, self.corner_mouth, self.side_mouth
        )
        object.__setattr__(self, "cushions", cushions)
        object.__setattr__(self, "pockets", pockets)

    # --- strings and spots -------------------------------------------------------------
    @property
    def head_string(self) -> float:
        """x of the head string: a quarter of the length from the head cushion."""
        return self.length / 4

    @property
    def head_spot(self) -> tuple[float, float]:
        return (self.length / 4, self.width / 2)

    @property
    def foot_spot(self) -> tuple[float, float]:
        return (3 * self.length / 4, self.width / 2)

    @property
    def center_spot(self) -> tuple[float, float]:
        return (self.length / 2, self.width / 2)

    @property
    def jaws(self) -> tuple[tuple[float, float], ...]:
        """Every jaw point (the ends of the cushions)."""
        return tuple(p for c in self.cushions for p in (c.start, c.end))

    def contains(self, x: float, y: float, margin: float = 0.0) -> bool:
        """True when a ball centred at (x, y) lies on the bed, clear of every cushion.

        `margin` shrinks the area further (ball in hand uses 0; tests use a round-off slack
        as a negative margin).
        """
        r = self.ball_radius + margin
        return r <= x <= self.length - r and r <= y <= self.width - r

    # --- arrays for the compiled kernels -----------------------------------------------
    def cushion_array(self) -> np.ndarray:
        """(C, 6) float64: start x, y, end x, y, normal x, y of each cushion."""
        return np.array([[*c.start, *c.end, *c.normal] for c in self.cushions], dtype=np.float64)

    def jaw_array(self) -> np.ndarray:
        """(J, 2) float64 jaw points."""
        return np.array(self.jaws, dtype=np.float64)

    def pocket_array(self) -> np.ndarray:
        """(P, 6) float64: jaw A x, y, jaw B x, y, outward normal x, y of each mouth."""
        return np.array(
            [[*p.jaws[0], *p.jaws[1], *p.outward] for p in self.pockets], dtype=np.float64
        )

    def pocket_centers(self) -> np.ndarray:
        """(P, 2) float64 drop-circle centres."""
        return np.array([p.center for p in self.pockets], dtype=np.float64)

    def to_dict(self) -> dict:
        """Plain data for clients: sizes, cushions, jaws and pockets."""
        return {
            "length": self.length,
            "width": self.width,
            "ball_radius": self.ball_radius,
            "head_string": self.head_string,
            "head_spot": list(self.head_spot),
            "foot_spot": list(self.foot_spot),
            "cushions": [
                {"start": list(c.start), "end": list(c.end), "normal": list(c.normal)}
                for c in self.cushions
            ],
            "pockets": [
                {
                    "name": p.name,
                    "jaws": [list(j) for j in p.jaws],
                    "center": list(p.center),
                    "radius": p.radius,
                }
                for p in self.pockets
            ],
        }


def _fields_by_name(value: object) -> object:
    """The list form of a stored table as the mapping the codec reads; others unchanged."""
    if isinstance(value, list | tuple):
        names = [f.name for f in fields(Table) if f.init]
        if not 2 <= len(value) <= len(names):
            raise ValueError(f"a table's field list has 2 to {len(names)} numbers")
        return dict(zip(names, value, strict=False))
    return value


def _build_geometry(
    length: float, width: float, corner_mouth: float, side_mouth: float
) -> tuple[tuple[Cushion, ...], tuple[Pocket, ...]]:
    a = corner_mouth / math.sqrt(2.0)  # each corner jaw's distance from the corner
    s = side_mouth / 2.0
    mid = length / 2.0
    cushions = (
        Cushion((a, 0.0), (mid - s, 0.0), (0.0, 1.0)),  # bottom left
        Cushion((mid + s, 0.0), (length - a, 0.0), (0.0, 1.0)),  # bottom right
        Cushion((length, a), (length, width - a), (-1.0, 0.0)),  # right (foot)
        Cushion((length - a, width), (mid + s, width), (0.0, -1.0)),  # top right
        Cushion((mid - s, width), (a, width), (0.0, -1.0)),  # top left
        Cushion((0.0, width - a), (0.0, a), (1.0, 0.0)),  # left (head)
    )
    d = 1.0 / math.sqrt(2.0)
    corner_r = corner_mouth / 2.0 + 0.01
    side_r = side_mouth / 2.0
    # The drop circle sits behind the mouth so that it touches the mouth line's middle.
    corner_back = corner_r - a / 2.0 * math.sqrt(2.0) + 0.02
    pockets = (
        Pocket(
            "bottom_left",
            ((0.0, a), (a, 0.0)),
            (-d, -d),
            (-corner_back * d, -corner_back * d),
            corner_r,
        ),
        Pocket(
            "bottom_side",
            ((mid - s, 0.0), (mid + s, 0.0)),
            (0.0, -1.0),
            (mid, -side_r * 0.6),
            side_r,
        ),
        Pocket(
            "bottom_right",
            ((length - a, 0.0), (length, a)),
            (d, -d),
            (length + corner_back * d, -corner_back * d),
            corner_r,
        ),
        Pocket(
            "top_right",
            ((length, width - a), (length - a, width)),
            (d, d),
            (length + corner_back * d, width + corner_back * d),
            corner_r,
        ),
        Pocket(
            "top_side",
            ((mid + s, width), (mid - s, width)),
            (0.0, 1.0),
            (mid, width + side_r * 0.6),
            side_r,
        ),
        Pocket(
            "top_left",
            ((a, width), (0.0, width - a)),
            (-d, d),
            (-corner_back * d, width + corner_back * d),
            corner_r,
        ),
    )
    return cushions, pockets
