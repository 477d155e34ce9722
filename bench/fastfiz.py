"""FastFiz's table, for asking how the computer would do under the tournaments' conditions.

The issue's runout goal is set under the computational-pool tournaments' execution noise,
and the tournaments were played in FastFiz (Stanford's simulator; read in its source,
`FastFiz.h` and `FastFiz.cpp`), on its table. That table is
smaller than the rooms' 9ft (2.236 x 1.116 m against 2.54 x 1.27 m) and its pockets have no
jaws: the rails are straight lines up to the pocket, and a ball drops the moment it crosses
the pocket's line: the line through the two points a ball's radius off each jaw point
along its rail's normal, where a ball's centre is when its edge reaches the rail's nose.
At the south-west corner that is `x + y = w/sqrt(2) + R`, w the 0.11 m corner width; at a
side pocket, the rail's line along the 0.12 m opening.
Nothing hangs on a shelf or rattles between the facings.

`fastfiz_table()` is our engine with that table: the size and mouths, and each pocket's
hole made a circle so large (`BULGE` of its arc onto the bed) that coming over it is
crossing that line within a tenth of a millimetre. The jaw points and facings stay but no
ball can reach one before it drops (each point lies a radius behind the line's end). The
rest of the physics stays ours: FastFiz's ball-ball friction of 0.01 at every speed throws
slow cuts less than ours, and its rails are plain dampers.

Only for benchmarks (`python -m bench.ai --table fastfiz`): the codec stores a table as
its sizes, so a game stored or sent to a planner process comes back with the rooms'
pockets.
"""

from __future__ import annotations

import math
from dataclasses import replace

from server.engine.table import Pocket, Table

FASTFIZ_LENGTH = 2.236  # m, FastFiz.h's TABLE_LENGTH
FASTFIZ_WIDTH = 1.116  # m, TABLE_WIDTH
FASTFIZ_CORNER_WIDTH = 0.11  # m, CORNER_POCKET_WIDTH
FASTFIZ_SIDE_WIDTH = 0.12  # m, SIDE_POCKET_WIDTH
BULGE = 0.0001  # m: how far the hole's arc reaches past the drop line, at its middle


class MouthLineTable(Table):
    """A table whose balls drop as their centres cross each pocket's drop line: the line
    between the two jaw points, moved a ball's radius into the bed (FastFiz's pockets)."""

    def __post_init__(self) -> None:
        super().__post_init__()
        normal_at = {
            end: cushion.normal for cushion in self.cushions for end in (cushion.start, cushion.end)
        }
        pockets = tuple(_drop_at_line(p, normal_at, self.ball_radius) for p in self.pockets)
        object.__setattr__(self, "pockets", pockets)


def _drop_at_line(
    pocket: Pocket, normal_at: dict[tuple[float, float], tuple[float, float]], radius: float
) -> Pocket:
    """`pocket` with a hole whose edge runs along its drop line: a circle through the line's
    two ends (each jaw point moved a radius along its cushion's inward normal), centred so
    far out that the arc bulges `BULGE` past the line."""
    (ax, ay), (bx, by) = (
        (jx + radius * normal_at[(jx, jy)][0], jy + radius * normal_at[(jx, jy)][1])
        for jx, jy in pocket.jaws
    )
    half_chord = math.dist((ax, ay), (bx, by)) / 2
    # Sagitta s of a circle of radius r over a chord of half-length c: (r - s)^2 + c^2 = r^2.
    hole_radius = (half_chord**2 / BULGE + BULGE) / 2
    back = hole_radius - BULGE
    ux, uy = pocket.outward
    hole = ((ax + bx) / 2 + back * ux, (ay + by) / 2 + back * uy)
    return replace(pocket, hole=hole, hole_radius=hole_radius, shelf=0.0)


def fastfiz_table() -> Table:
    """FastFiz's default table in our engine (its size, mouths and pockets)."""
    return MouthLineTable(
        FASTFIZ_LENGTH,
        FASTFIZ_WIDTH,
        corner_mouth=FASTFIZ_CORNER_WIDTH,
        side_mouth=FASTFIZ_SIDE_WIDTH,
    )
