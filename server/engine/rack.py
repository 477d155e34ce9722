"""Racks: the triangle for 8-ball and the diamond for 9-ball, with the cue ball on the head
spot; snooker's 15 reds behind the pink and the six colours on their spots, the cue ball in
the D; the three balls of carom on their start spots.

Real racks are never perfect: each ball sits on a lattice slightly wider than a ball
(0.05 mm) and is moved by a seeded jitter of at most 0.025 mm, so every neighbour gap lies
in [0, 0.1 mm].
"""

from __future__ import annotations

import math

import numpy as np

from .balls import BallSet
from .table import Table

LATTICE_GAP = 0.05e-3  # m added to the ball spacing
JITTER = 0.025e-3  # m, largest seeded displacement of a ball

SOLIDS = (1, 2, 3, 4, 5, 6, 7)
STRIPES = (9, 10, 11, 12, 13, 14, 15)

# Snooker's ball ids: 1-15 the reds, then the colours in the order they are potted (and
# of their value, 2 to 7).
REDS = tuple(range(1, 16))
COLOURS: dict[str, int] = {
    "yellow": 16,
    "green": 17,
    "brown": 18,
    "blue": 19,
    "pink": 20,
    "black": 21,
}
# Three-cushion's balls: the white and the yellow cue balls, and the red.
WHITE, YELLOW, RED = 0, 1, 2
GAMES = ("eight_ball", "nine_ball", "snooker", "three_cushion")


def _slots(rows: list[int], table: Table) -> list[tuple[float, float]]:
    """Centres of a rack whose rows (apex first) have the given lengths, apex on the foot
    spot and rows growing towards the foot cushion."""
    d = 2 * table.ball_radius + LATTICE_GAP
    fx, fy = table.foot_spot
    out = []
    for r, count in enumerate(rows):
        x = fx + r * d * math.sqrt(3) / 2
        for k in range(count):
            y = fy + (k - (count - 1) / 2) * d
            out.append((x, y))
    return out


def _eight_ball_order(rng: np.random.Generator) -> list[int]:
    # slots: row0 [0], row1 [1,2], row2 [3,4,5], row3 [6..9], row4 [10..14]
    solids, stripes = list(SOLIDS), list(STRIPES)
    rng.shuffle(solids)
    rng.shuffle(stripes)
    order: list[int | None] = [None] * 15
    order[4] = 8  # centre of the third row
    if rng.random() < 0.5:
        order[10], order[14] = solids.pop(), stripes.pop()
    else:
        order[10], order[14] = stripes.pop(), solids.pop()
    rest = solids + stripes
    rng.shuffle(rest)
    for i in range(15):
        if order[i] is None:
            order[i] = rest.pop()
    return [int(b) for b in order]  # type: ignore[arg-type]


def _nine_ball_order(rng: np.random.Generator) -> list[int]:
    # slots: row0 [0], row1 [1,2], row2 [3,4,5], row3 [6,7], row4 [8]
    rest = [2, 3, 4, 5, 6, 7, 8]
    rng.shuffle(rest)
    order = [1, rest[0], rest[1], rest[2], 9, rest[3], rest[4], rest[5], rest[6]]
    return [int(b) for b in order]


def _snooker_placement(table: Table, rng: np.random.Generator) -> dict[int, tuple[float, float]]:
    """WPBSA Section 3 Rule 2 (Position of Balls): the reds in a tight triangle, the apex
    ball as near the pink as possible without touching it, its base parallel to and nearest
    the top cushion; the colours on their spots. The cue ball starts in the D, halfway
    between the brown and green spots (the player places it: "in-hand")."""
    spots = table.spots
    px, py = spots["pink"]
    d = 2 * table.ball_radius + LATTICE_GAP
    apex = (px + d, py)
    slots = [
        (apex[0] + r * d * math.sqrt(3) / 2, py + (k - r / 2) * d)
        for r in range(5)
        for k in range(r + 1)
    ]
    placement = {COLOURS[name]: spots[name] for name in COLOURS}
    placement.update(_jittered(dict(zip(REDS, slots, strict=True)), rng))
    bx, by = spots["brown"]
    placement[0] = (bx, by + table.cut.d_radius / 2)
    return placement


def _jittered(
    slots: dict[int, tuple[float, float]], rng: np.random.Generator
) -> dict[int, tuple[float, float]]:
    """Each ball moved by the seeded jitter (`JITTER`), in the order given."""
    out = {}
    for ball, (x, y) in slots.items():
        angle = rng.uniform(0, 2 * math.pi)
        shift = rng.uniform(0, JITTER)
        out[ball] = (x + shift * math.cos(angle), y + shift * math.sin(angle))
    return out


def carom_placement(table: Table, opener_ball: int = WHITE) -> dict[int, tuple[float, float]]:
    """The opening position of three-cushion (UMB Three cushion, the opening): the red on
    the foot spot, the opponent's cue ball on the head spot, the opener's cue ball (the
    white unless told) on the head string 182.5 mm to the right of it."""
    spots = table.spots
    other = YELLOW if opener_ball == WHITE else WHITE
    return {RED: spots["foot"], other: spots["head"], opener_ball: spots["break_right"]}


def rack(game: str, table: Table, seed: int | None = 0) -> BallSet:
    """A fresh rack for `game` ("eight_ball", "nine_ball": cue ball on the head spot;
    "snooker": `_snooker_placement`; "three_cushion": `carom_placement`, no jitter)."""
    rng = np.random.default_rng(seed)
    if game == "three_cushion":
        if table.style != "carom":
            raise ValueError("a three-cushion rack needs a carom table (Table.carom())")
        return BallSet.place(carom_placement(table))
    if game == "snooker":
        if table.style != "snooker":
            raise ValueError("a snooker rack needs a snooker table (Table.snooker())")
        return BallSet.place(_snooker_placement(table, rng))
    if game == "eight_ball":
        slots = _slots([1, 2, 3, 4, 5], table)
        order = _eight_ball_order(rng)
    elif game == "nine_ball":
        slots = _slots([1, 2, 3, 2, 1], table)
        order = _nine_ball_order(rng)
    else:
        raise ValueError(f"unknown game {game!r}; choose one of {GAMES}")
    placement: dict[int, tuple[float, float]] = {0: table.head_spot}
    for ball, (x, y) in zip(order, slots, strict=True):
        angle = rng.uniform(0, 2 * math.pi)
        shift = rng.uniform(0, JITTER)
        placement[ball] = (x + shift * math.cos(angle), y + shift * math.sin(angle))
    return BallSet.place(placement)


def rack_slots(game: str, table: Table) -> list[tuple[float, float]]:
    """The nominal (unjittered) rack centres, apex first; rules use them to re-spot."""
    rows = [1, 2, 3, 4, 5] if game == "eight_ball" else [1, 2, 3, 2, 1]
    return _slots(rows, table)
