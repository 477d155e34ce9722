"""Table styles: what differs between a pool table and a snooker table besides its size.

A style names the shape of its corner and side pockets (facing angle, shelf, hole), the
weight of its balls and the markings on its cloth (lines across the table, arcs, spots),
so `Table` builds any of them from one description and a client draws any of them from
`Table.to_dict`. A carom table will be a style without pockets.

Snooker (WPBSA "Official Rules of the Games of Snooker and English Billiards", Section 1
Equipment): playing area 3569 x 1778 mm (11 ft 8 1/2 in x 5 ft 10 in); the baulk line
737 mm (29 in) from the face of the bottom cushion; the D a semicircle of 292 mm
(11 1/2 in) radius centred on the middle of the baulk line, on the baulk side; the spots:
yellow at the right of the D (seen from the baulk end), green at its left, brown at the
middle of the baulk line, blue at the centre of the table, pink midway between the centre
and the face of the top cushion, black 324 mm (12 3/4 in) from the face of the top
cushion; balls 52.5 mm (+- 0.05 mm) in diameter.

The WPBSA gives the pocket openings only as its templates; the mouths here are the widths
at which our sharp-pointed jaws accept what pooltool 0.6.0's "Generic Snooker" pockets
(rounded jaws of 91 mm and 63.5 mm radius, openings 83 and 75 mm between the curves)
accept (`bench.pockets`, `tests/engine/test_snooker.py`).
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class PocketCut:
    """One kind of pocket (corner or side) behind its mouth: the facing angle between the
    cushion nose and the facing (degrees), the shelf from the middle of the mouth line to
    the edge of the hole (m), and the hole's radius (m)."""

    facing_deg: float
    shelf: float
    hole: float


@dataclass(frozen=True)
class Arc:
    """A drawn arc: centre, radius and the angles it runs between (degrees, counter
    clockwise, 0 along +x)."""

    center: tuple[float, float]
    radius: float
    start_deg: float
    end_deg: float


@dataclass(frozen=True)
class Spot:
    """A named spot on the long middle line, or `across` m beside it (+y): at `fraction`
    of the length from the head cushion, or `from_head` m from it, or `from_foot` m from
    the foot (top) cushion; the first given counts."""

    name: str
    fraction: float | None = None
    from_head: float | None = None
    from_foot: float | None = None
    across: float = 0.0

    def at(self, length: float, width: float) -> tuple[float, float]:
        if self.fraction is not None:
            x = self.fraction * length
        elif self.from_head is not None:
            x = self.from_head
        else:
            x = length - (self.from_foot or 0.0)
        return (x, width / 2 + self.across)


POOL_SPOTS = (Spot("head", fraction=0.25), Spot("foot", fraction=0.75))


@dataclass(frozen=True)
class TableStyle:
    """How one kind of table is cut and marked.

    corner / side: its pockets (None: a table without pockets, four whole cushions).
    ball_mass: kg. physics: `PhysicsParams` fields whose value differs on this table (its
    cloth, its cushions), as (name, value) pairs. baulk_line: distance of the line across the
    table from the head (baulk) cushion in m, or None for the pool head string (a quarter
    of the length). d_radius: the D's radius (m), 0 without one. spots: the named spots.
    """

    name: str
    corner: PocketCut | None
    side: PocketCut | None
    ball_mass: float
    baulk_line: float | None = None
    d_radius: float = 0.0
    spot_rules: tuple[Spot, ...] = POOL_SPOTS
    physics: tuple[tuple[str, float], ...] = ()

    @property
    def pocketed(self) -> bool:
        """The table has pockets."""
        return self.corner is not None and self.side is not None

    def head_line(self, length: float) -> float:
        """x of the line across the table at the head end (head string, baulk line)."""
        return self.baulk_line if self.baulk_line is not None else length / 4

    def spots(self, length: float, width: float) -> dict[str, tuple[float, float]]:
        """The named spots on the cloth, by their rules."""
        return {spot.name: spot.at(length, width) for spot in self.spot_rules}

    def arcs(self, length: float, width: float) -> tuple[Arc, ...]:
        """The D (a semicircle on the baulk side of the baulk line), if the style has one."""
        if self.d_radius <= 0:
            return ()
        return (Arc((self.head_line(length), width / 2), self.d_radius, 90.0, 270.0),)


# Shelves and holes: pooltool 0.6.0's Generic Snooker pocket depths (36 mm, 0.95 in) and
# radii (43 mm, 1.68 in); the facing angles are what lets our sharp points accept what its
# rounded jaws accept. Ball mass: 142 g, a match set's weight (the WPBSA asks only that
# a set's balls weigh within 3 g of each other).
BAULK_LINE = 0.737
D_RADIUS = 0.292
SNOOKER = TableStyle(
    "snooker",
    corner=PocketCut(135.0, 0.036, 0.043),
    side=PocketCut(100.0, 0.0241, 0.0427),
    ball_mass=0.142,
    baulk_line=BAULK_LINE,
    d_radius=D_RADIUS,
    spot_rules=(
        # Seen from the baulk end (x grows away from it) the right is -y.
        Spot("yellow", from_head=BAULK_LINE, across=-D_RADIUS),
        Spot("green", from_head=BAULK_LINE, across=D_RADIUS),
        Spot("brown", from_head=BAULK_LINE),
        Spot("blue", fraction=0.5),
        Spot("pink", fraction=0.75),
        Spot("black", from_foot=0.324),
    ),
)


# Carom (UMB, "Règlement sportif / Sporting Code", Carom billiards, Equipment: the match
# table's playing area 2840 x 1420 mm measured between the cushion noses, balls 61 to
# 61.5 mm and 205 to 220 g, cushion height 37 mm +- 1 mm). The start spots (UMB, Three
# cushion, "position of the balls at the opening"): the red on the top (foot) spot, the
# opponent's cue ball on the head spot, the opener's on the head string 182.5 mm to one
# side of it (pooltool 0.6.0's three-cushion layout puts it on the same spot).
# Balls and cloth: pooltool 0.6.0's BILLIARD_GENERIC ball parameters (R 30.75 mm, 210 g,
# u_s 0.2, u_r 0.01, e_c 0.85, f_c 0.15) and its billiard table's cushion height (37 mm):
# the nose is 37 / 61.5 = 60.2 % of the ball's height (a pool nose is 63.5 %).
CAROM_BREAK_OFFSET = 0.1825
CAROM_CUSHION_HEIGHT = 0.037
CAROM_BALL_DIAMETER = 0.0615
CAROM = TableStyle(
    "carom",
    corner=None,
    side=None,
    ball_mass=0.210,
    spot_rules=(
        Spot("head", fraction=0.25),
        Spot("center", fraction=0.5),
        Spot("foot", fraction=0.75),
        # Seen from the head end the opener's right is -y.
        Spot("break_right", fraction=0.25, across=-CAROM_BREAK_OFFSET),
        Spot("break_left", fraction=0.25, across=CAROM_BREAK_OFFSET),
    ),
    physics=(
        ("cushion_nose", CAROM_CUSHION_HEIGHT / CAROM_BALL_DIAMETER),
        ("f_cushion", 0.15),
        # pooltool's spinning friction, u_sp = 10 * 2 / 5 / 9 R, for this R.
        ("u_spin", 10 * 2 / 5 / 9 * CAROM_BALL_DIAMETER / 2),
    ),
)
