"""Table geometry: the playing surface, its cushions, the pocket jaws and the pockets.

SI units. The origin is the bottom-left corner of the playing surface measured at the
cushion noses; x runs along the long side. The head (where the break is taken from) is the
left quarter, the rack sits on the foot spot in the right quarter.

A cushion is a straight segment of a rail between two pocket mouths. Its two ends are the
jaws (the "points" of the pocket). From each point a facing, the cushion's cut side, runs
back into the pocket at the WPA facing angle (142 degrees to the cushion nose at a corner,
104 at a side pocket), so the throat narrows behind the mouth. Behind the mouth line lies
the shelf, then the hole: a ball drops when its centre is over the hole (within the hole's
radius of its centre), not when it crosses the mouth line, so a slow ball can stop on the
shelf (a hanger) and a ball can rattle between the facings and come back out.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from dataclasses import dataclass, field, fields
from typing import TYPE_CHECKING, Annotated, Any

import numpy as np
from pydantic import Field

from .styles import CAROM, CAROM_BALL_DIAMETER, SNOOKER, Arc, PocketCut, TableStyle

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
# Facing angles between the cushion nose and the pocket facing (WPA: 142 +-1 and 104 +-1).
CORNER_FACING_DEG = 142.0
SIDE_FACING_DEG = 104.0
# Shelf: from the middle of the mouth line to the edge of the hole (WPA: corner 1 to 2.25 in,
# side 0 to 0.375 in; Roger Long's survey of real corners: 3/4 to 2 in). 38 mm is where
# pooltool 0.6.0's corner lets a ball go before it drops.
CORNER_SHELF = 0.038
SIDE_SHELF = 0.00635
# Hole radii (pooltool 0.6.0's pocket radii).
CORNER_HOLE = 0.062
SIDE_HOLE = 0.0645

POOL = TableStyle(
    "pool",
    corner=PocketCut(CORNER_FACING_DEG, CORNER_SHELF, CORNER_HOLE),
    side=PocketCut(SIDE_FACING_DEG, SIDE_SHELF, SIDE_HOLE),
    ball_mass=BALL_MASS,
)
STYLES: dict[str, TableStyle] = {style.name: style for style in (POOL, SNOOKER, CAROM)}

# Snooker (WPBSA 1.1 The Standard Table, 1.2 Balls; `styles.py`): playing area, ball
# radius, and the jaw-to-jaw mouths our sharp points need to accept what pooltool's
# rounded snooker jaws do.
SNOOKER_SIZE = (3.569, 1.778)
SNOOKER_BALL_RADIUS = 0.02625
SNOOKER_CORNER_MOUTH = 0.094
SNOOKER_SIDE_MOUTH = 0.128
# Carom (UMB; `styles.py`): the match table's playing area and the ball's radius.
CAROM_SIZE = (2.84, 1.42)
CAROM_BALL_RADIUS = CAROM_BALL_DIAMETER / 2


def style_named(name: str) -> TableStyle:
    """The style `name`; ValueError for one that does not exist."""
    try:
        return STYLES[name]
    except KeyError:
        raise ValueError(f"unknown table style {name!r}; choose one of {sorted(STYLES)}") from None


@dataclass(frozen=True)
class Cushion:
    """A straight cushion nose from `start` to `end`; `normal` points into the playing area."""

    start: tuple[float, float]
    end: tuple[float, float]
    normal: tuple[float, float]


@dataclass(frozen=True)
class Pocket:
    """A pocket: the mouth between two jaw points, two facings, a shelf and the hole.

    `outward` is the unit normal of the mouth line pointing into the pocket; `center` and
    `radius` are the circle clients draw, and a pocketed ball rests at `center` (both as
    before the pockets had shelves, so stored states and drawings are unchanged). The
    physics uses `hole` and `hole_radius`: a ball whose centre comes within `hole_radius`
    of `hole` drops. `facings` are the two cut sides, one from each jaw point (in the
    order of `jaws`) into the pocket; `shelf` is the distance from the middle of the
    mouth line to the edge of the hole.
    """

    name: str
    jaws: tuple[tuple[float, float], tuple[float, float]]
    outward: tuple[float, float]
    center: tuple[float, float]
    radius: float
    shelf: float = 0.0
    facings: tuple[tuple[tuple[float, float], tuple[float, float]], ...] = ()
    hole: tuple[float, float] = (0.0, 0.0)
    hole_radius: float = 0.0


@dataclass(frozen=True)
class Table:
    """A table: playing-surface size, cushions, jaws and pockets (all derived), cut and
    marked in its `style` ("pool" or "snooker", `styles.py`).

    Stored through the codec (`server.codec.to_data`) as its constructor fields only,
    `{"length", "width", "ball_radius", "corner_mouth", "side_mouth"}` and `"style"` when
    it is not "pool" (so a pool table's stored form is what it always was); the geometry
    is rebuilt on load. The codec also loads the older stored form, those fields as a
    list. `to_dict` is not storage: it is the derived geometry browsers draw.
    """

    length: float
    width: float
    ball_radius: float = BALL_RADIUS
    corner_mouth: float = CORNER_MOUTH
    side_mouth: float = SIDE_MOUTH
    # Not stored when "pool", so a pool table's stored form is what it always was.
    style: Annotated[str, Field(exclude_if=lambda style: style == "pool")] = "pool"
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
    def snooker(cls) -> Table:
        """The WPBSA snooker table: 3569 x 1778 mm, 52.5 mm balls, snooker pockets."""
        length, width = SNOOKER_SIZE
        return cls(
            length,
            width,
            SNOOKER_BALL_RADIUS,
            SNOOKER_CORNER_MOUTH,
            SNOOKER_SIDE_MOUTH,
            style=SNOOKER.name,
        )

    @classmethod
    def carom(cls) -> Table:
        """The UMB match carom table: 2840 x 1420 mm, 61.5 mm balls, no pockets."""
        length, width = CAROM_SIZE
        return cls(length, width, CAROM_BALL_RADIUS, 0.0, 0.0, style=CAROM.name)

    @property
    def cut(self) -> TableStyle:
        """The style this table is cut and marked in."""
        return style_named(self.style)

    def fields(self) -> list[float | str]:
        """The constructor fields in order: the list form `from_fields` reads (a shot's
        stored table); the style only when it is not "pool"."""
        values: list[float | str] = [
            getattr(self, f.name) for f in dataclasses.fields(self) if f.init and f.name != "style"
        ]
        return values if self.style == POOL.name else [*values, self.style]

    @classmethod
    def from_fields(cls, values: Sequence[float | str]) -> Table:
        """A table from its constructor fields in order: the list form stored before the
        codec (`[length, width, ball_radius, corner_mouth, side_mouth]`, then the style)."""
        data = _fields_by_name(list(values))
        assert isinstance(data, dict)
        style = str(data.pop("style", POOL.name))
        return cls(**{name: float(v) for name, v in data.items()}, style=style)

    @classmethod
    def __get_pydantic_core_schema__(cls, source: Any, handler: GetCoreSchemaHandler) -> CoreSchema:
        """The codec's schema for the fields, taking the older list form as well."""
        from pydantic_core import core_schema

        return core_schema.no_info_before_validator_function(_fields_by_name, handler(source))

    def __post_init__(self) -> None:
        cushions, pockets = _build_geometry(
            self.length,
            self.width,
            self.corner_mouth,
            self.side_mouth,
            self.ball_radius,
            style_named(self.style),
        )
        object.__setattr__(self, "cushions", cushions)
        object.__setattr__(self, "pockets", pockets)

    # --- strings and spots -------------------------------------------------------------
    @property
    def head_string(self) -> float:
        """x of the head string: a quarter of the length from the head cushion (pool); the
        baulk line on a snooker table."""
        return self.cut.head_line(self.length)

    @property
    def spots(self) -> dict[str, tuple[float, float]]:
        """The named spots on the cloth (pool: head, foot; snooker: the six colours')."""
        return self.cut.spots(self.length, self.width)

    @property
    def arcs(self) -> tuple[Arc, ...]:
        """The arcs drawn on the cloth (snooker's D)."""
        return self.cut.arcs(self.length, self.width)

    def in_d(self, x: float, y: float) -> bool:
        """A ball centred at (x, y) is in the D: on or behind the baulk line and within the
        D's radius of its centre (snooker), to a nanometre (the spots on the D's edge are
        sums that round)."""
        cut = self.cut
        if cut.d_radius <= 0:
            return False
        cx, cy = cut.head_line(self.length), self.width / 2
        return x <= cx + 1e-9 and math.hypot(x - cx, y - cy) <= cut.d_radius + 1e-9

    @property
    def head_spot(self) -> tuple[float, float]:
        return (self.length / 4, self.width / 2)

    @property
    def foot_spot(self) -> tuple[float, float]:
        return (3 * self.length / 4, self.width / 2)

    @property
    def jaws(self) -> tuple[tuple[float, float], ...]:
        """Every jaw point (the ends of the cushions); none on a table without pockets,
        whose cushions meet in its corners."""
        if not self.pockets:
            return ()
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

    def facings(self) -> tuple[tuple[tuple[float, float], tuple[float, float]], ...]:
        """The facing (start, end) that runs from each jaw point, in `jaws` order."""
        by_jaw = {j: f for p in self.pockets for j, f in zip(p.jaws, p.facings, strict=True)}
        return tuple(by_jaw[j] for j in self.jaws)

    def jaw_array(self) -> np.ndarray:
        """(J, 6) float64: jaw point x, y, the far end x, y of its facing, and the facing's
        unit normal x, y (pointing into the pocket's throat)."""
        rows = []
        for (jx, jy), (_, (ex, ey)) in zip(self.jaws, self.facings(), strict=True):
            fx, fy = ex - jx, ey - jy
            length = math.hypot(fx, fy)
            nx, ny = -fy / length, fx / length
            # Towards the mouth's middle, i.e. into the throat.
            pocket = next(p for p in self.pockets if (jx, jy) in p.jaws)
            mx = (pocket.jaws[0][0] + pocket.jaws[1][0]) / 2 - jx
            my = (pocket.jaws[0][1] + pocket.jaws[1][1]) / 2 - jy
            if nx * mx + ny * my < 0:
                nx, ny = -nx, -ny
            rows.append([jx, jy, ex, ey, nx, ny])
        return np.array(rows, dtype=np.float64).reshape(len(rows), 6)

    def pocket_array(self) -> np.ndarray:
        """(P, 3) float64: hole centre x, y and radius of each pocket."""
        rows = [[*p.hole, p.hole_radius] for p in self.pockets]
        return np.array(rows, dtype=np.float64).reshape(len(rows), 3)

    def pocket_centers(self) -> np.ndarray:
        """(P, 2) float64 drawn centres (where a pocketed ball rests)."""
        return np.array([p.center for p in self.pockets], dtype=np.float64).reshape(-1, 2)

    def to_dict(self) -> dict[str, Any]:
        """Plain data for clients: sizes, cushions, jaws and pockets."""
        return {
            "length": self.length,
            "width": self.width,
            "ball_radius": self.ball_radius,
            "style": self.style,
            "spots": {name: list(xy) for name, xy in self.spots.items()},
            "arcs": [
                {
                    "center": list(a.center),
                    "radius": a.radius,
                    "start_deg": a.start_deg,
                    "end_deg": a.end_deg,
                }
                for a in self.arcs
            ],
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
    length: float,
    width: float,
    corner_mouth: float,
    side_mouth: float,
    ball_radius: float,
    style: TableStyle = POOL,
) -> tuple[tuple[Cushion, ...], tuple[Pocket, ...]]:
    if style.corner is None or style.side is None:
        return _closed_cushions(length, width), ()
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
    mouths = (
        ("bottom_left", ((0.0, a), (a, 0.0)), (-d, -d)),
        ("bottom_side", ((mid - s, 0.0), (mid + s, 0.0)), (0.0, -1.0)),
        ("bottom_right", ((length - a, 0.0), (length, a)), (d, -d)),
        ("top_right", ((length, width - a), (length - a, width)), (d, d)),
        ("top_side", ((mid + s, width), (mid - s, width)), (0.0, 1.0)),
        ("top_left", ((a, width), (0.0, width - a)), (-d, d)),
    )
    # The drawn circles (and where a pocketed ball rests), exactly as before pockets had
    # shelves, so stored states and drawings do not change: a side circle touches the
    # middle of the mouth line, a corner circle sits 2 cm further back.
    corner_r = corner_mouth / 2.0 + 0.01
    side_r = side_mouth / 2.0
    back = corner_r - a / 2.0 * math.sqrt(2.0) + 0.02
    drawn = {
        "bottom_left": ((-back * d, -back * d), corner_r),
        "bottom_side": ((mid, -side_r * 0.6), side_r),
        "bottom_right": ((length + back * d, -back * d), corner_r),
        "top_right": ((length + back * d, width + back * d), corner_r),
        "top_side": ((mid, width + side_r * 0.6), side_r),
        "top_left": ((-back * d, width + back * d), corner_r),
    }
    # Each jaw point's cushion: the unit vector along its nose away from the pocket, and its
    # inward normal.
    along: dict[tuple[float, float], tuple[tuple[float, float], tuple[float, float]]] = {}
    for c in cushions:
        ex, ey = c.end[0] - c.start[0], c.end[1] - c.start[1]
        n = math.hypot(ex, ey) or 1.0  # (a degenerate table still builds)
        along[c.start] = ((ex / n, ey / n), c.normal)
        along[c.end] = ((-ex / n, -ey / n), c.normal)
    pockets = []
    for name, jaws, (ux, uy) in mouths:
        cut = style.side if "side" in name else style.corner
        angle = math.radians(cut.facing_deg)
        shelf, hole = cut.shelf, cut.hole
        mx = (jaws[0][0] + jaws[1][0]) / 2
        my = (jaws[0][1] + jaws[1][1]) / 2
        hole_center = (mx + (shelf + hole) * ux, my + (shelf + hole) * uy)
        facings = []
        for jaw in jaws:
            (ex, ey), (nx, ny) = along[jaw]
            # The nose turned by the facing angle, out of the bed.
            fx = math.cos(angle) * ex - math.sin(angle) * nx
            fy = math.cos(angle) * ey - math.sin(angle) * ny
            # Deep enough that no ball gets past the hole without being over it.
            depth = (shelf + hole + ball_radius) / max(fx * ux + fy * uy, 0.5)
            facings.append((jaw, (jaw[0] + depth * fx, jaw[1] + depth * fy)))
        center, drawn_r = drawn[name]
        pockets.append(
            Pocket(name, jaws, (ux, uy), center, drawn_r, shelf, tuple(facings), hole_center, hole)
        )
    return cushions, tuple(pockets)


def _closed_cushions(length: float, width: float) -> tuple[Cushion, ...]:
    """The four whole cushions of a table without pockets, in the pool table's order
    (bottom, right, top, left), meeting in the corners."""
    return (
        Cushion((0.0, 0.0), (length, 0.0), (0.0, 1.0)),  # bottom
        Cushion((length, 0.0), (length, width), (-1.0, 0.0)),  # right (foot)
        Cushion((length, width), (0.0, width), (0.0, -1.0)),  # top
        Cushion((0.0, width), (0.0, 0.0), (1.0, 0.0)),  # left (head)
    )
