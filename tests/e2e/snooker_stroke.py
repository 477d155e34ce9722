"""What a newcomer at the snooker table decides before each stroke, from what the page
shows: the balls where they are drawn, the ball(s) on, the table's pockets and the D.

Plain geometry, as a person sights a shot: a pot along a clear line with the ghost ball
(the cue ball's centre 2R behind the object ball, on the line to the pocket), else a full
hit at a ball on in plain view, else a one-cushion path to it (a mirror image across the
cushion), else a stroke straight at a ball on through whatever is in the way. The server's
miss rule (WPBSA 3.12, `server/rules/snooker.py`) calls a foul a miss when a ball on could
be struck at both edges in a straight line, so a ball on in plain view is always hit first.

`attempt` counts how often the same table has come back (the computer may have the
newcomer play again after a foul): each repeat takes the next candidate, so a stroke that
failed is not played again unchanged.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

Point = tuple[float, float]

MAX_CUT = math.radians(70)  # thinner cuts are beyond a newcomer
CORNER_ENTRY = math.radians(45)  # off the pocket's diagonal
SIDE_ENTRY = math.radians(35)  # off the side pocket's perpendicular
MIN_SPEED, MAX_SPEED = 0.9, 4.0  # m/s of the cue ball: moderate strokes
# Off a cushion, firmly: a rolling ball's topspin bends its path after the cushion back
# toward where it came from, over a distance that grows with the speed (slower kicks fall
# short of the mirror line on the engine).
KICK_SPEED = 4.0


@dataclass(frozen=True)
class Stroke:
    """Where the cue points (radians from +x), how fast the cue ball goes (m/s), a point
    on the line of aim the person presses on, and what the stroke is meant to do."""

    angle: float
    speed: float
    press: Point
    ball: int
    kind: str  # "pot", "hit", "cushion" or "blind"


@dataclass(frozen=True)
class Layout:
    """The table as the page draws it: size, ball radius, pocket mouths, the D."""

    length: float
    width: float
    radius: float
    mouths: tuple[tuple[Point, Point], ...]  # (centre of the mouth, into the pocket)
    d_centre: Point
    d_radius: float

    @classmethod
    def of(cls, table: dict) -> Layout:
        """From the page's `state.table`."""
        mouths = []
        for pocket in table["pockets"]:
            (ax, ay), (bx, by) = pocket["jaws"]
            mid = ((ax + bx) / 2, (ay + by) / 2)
            cx, cy = pocket["center"]
            n = math.hypot(cx - mid[0], cy - mid[1])
            mouths.append((mid, ((cx - mid[0]) / n, (cy - mid[1]) / n)))
        arc = table["arcs"][0]
        return cls(
            length=table["length"],
            width=table["width"],
            radius=table["ball_radius"],
            mouths=tuple(mouths),
            d_centre=tuple(arc["center"]),
            d_radius=arc["radius"],
        )


def clear(a: Point, b: Point, others: Iterable[Point], reach: float) -> bool:
    """No centre of `others` within `reach` of the segment a-b."""
    dx, dy = b[0] - a[0], b[1] - a[1]
    length2 = dx * dx + dy * dy or 1e-18
    for ox, oy in others:
        t = min(1.0, max(0.0, ((ox - a[0]) * dx + (oy - a[1]) * dy) / length2))
        if math.hypot(a[0] + t * dx - ox, a[1] + t * dy - oy) < reach:
            return False
    return True


def _unit(a: Point, b: Point) -> tuple[Point, float]:
    d = math.hypot(b[0] - a[0], b[1] - a[1]) or 1e-12
    return ((b[0] - a[0]) / d, (b[1] - a[1]) / d), d


def _angle_between(u: Point, v: Point) -> float:
    return math.acos(max(-1.0, min(1.0, u[0] * v[0] + u[1] * v[1])))


def _speed(travel: float, cut: float = 0.0) -> float:
    """Enough for the object ball to reach the pocket with some to spare, no more."""
    return min(MAX_SPEED, max(MIN_SPEED, (0.8 + 0.7 * travel) / max(math.cos(cut), 0.45)))


def _on_cloth(p: Point, layout: Layout) -> bool:
    r = layout.radius
    return r <= p[0] <= layout.length - r and r <= p[1] <= layout.width - r


def pots(layout: Layout, cue: Point, balls: dict[int, Point], on: Sequence[int]) -> list[Stroke]:
    """Every pot of a ball on along clear lines, the easiest first."""
    return [s for _, s in _scored_pots(layout, cue, balls, on)]


def _scored_pots(
    layout: Layout, cue: Point, balls: dict[int, Point], on: Sequence[int]
) -> list[tuple[float, Stroke]]:
    """The pots with their cost (longer lines and thinner cuts cost more), cheapest first."""
    r = layout.radius
    found: list[tuple[float, Stroke]] = []
    for ball in on:
        target = balls[ball]
        others = [p for b, p in balls.items() if b != ball]
        for k, (mouth, inward) in enumerate(layout.mouths):
            u, run = _unit(target, mouth)
            entry = CORNER_ENTRY if k % 3 != 1 else SIDE_ENTRY  # pockets listed 3 a side
            if _angle_between(u, inward) > entry:
                continue
            ghost = (target[0] - 2 * r * u[0], target[1] - 2 * r * u[1])
            aim, reach = _unit(cue, ghost)
            cut = _angle_between(aim, u)
            if cut > MAX_CUT or not _on_cloth(ghost, layout):
                continue
            if not clear(cue, ghost, others, 2 * r) or not clear(target, mouth, others, 2 * r):
                continue
            cost = (reach + 2 * run) / math.cos(cut) ** 2
            stroke = Stroke(
                math.atan2(aim[1], aim[0]), _speed(reach + run, cut), ghost, ball, "pot"
            )
            found.append((cost, stroke))
    return sorted(found, key=lambda f: f[0])


def hits(layout: Layout, cue: Point, balls: dict[int, Point], on: Sequence[int]) -> list[Stroke]:
    """A full hit at each ball on in plain view (nothing within 2R of the line), nearest
    first."""
    r = layout.radius
    found = []
    for ball in on:
        target = balls[ball]
        others = [p for b, p in balls.items() if b != ball]
        u, d = _unit(cue, target)
        ghost = (target[0] - 2 * r * u[0], target[1] - 2 * r * u[1])
        if clear(cue, ghost, others, 2 * r):
            found.append((d, Stroke(math.atan2(u[1], u[0]), _speed(d), ghost, ball, "hit")))
    return [s for _, s in sorted(found, key=lambda f: f[0])]


def cushions(
    layout: Layout, cue: Point, balls: dict[int, Point], on: Sequence[int]
) -> list[Stroke]:
    """One cushion, then a ball on: aim at the ball's mirror image across the line the cue
    ball's centre bounces on (R from the cushion), both legs clear; shortest first."""
    r = layout.radius
    found = []
    for ball in on:
        tx, ty = balls[ball]
        others = [p for b, p in balls.items() if b != ball]
        mirrors = [(tx, 2 * r - ty), (tx, 2 * (layout.width - r) - ty),
                   (2 * r - tx, ty), (2 * (layout.length - r) - tx, ty)]  # fmt: skip
        for mx, my in mirrors:
            bounce = _bounce(cue, (mx, my), layout)
            if bounce is None or _near_pocket(bounce, layout):
                continue
            if clear(cue, bounce, others, 2 * r) and clear(bounce, (tx, ty), others, 2 * r):
                u, d = _unit(cue, (mx, my))
                stroke = Stroke(math.atan2(u[1], u[0]), KICK_SPEED, bounce, ball, "cushion")
                found.append((d, stroke))
    return [s for _, s in sorted(found, key=lambda f: f[0])]


def _bounce(cue: Point, mirror: Point, layout: Layout) -> Point | None:
    """Where the line from the cue ball to a mirror image meets the bounce line."""
    r = layout.radius
    (cx, cy), (mx, my) = cue, mirror
    for line, axis in ((r, 1), (layout.width - r, 1), (r, 0), (layout.length - r, 0)):
        a, b = (cy, my) if axis else (cx, mx)
        if (a - line) * (b - line) >= 0:
            continue
        t = (line - a) / (b - a)
        p = (cx + t * (mx - cx), cy + t * (my - cy))
        if _on_cloth(p, layout) or abs(p[axis] - line) < 1e-9:
            return p
    return None


def _near_pocket(p: Point, layout: Layout) -> bool:
    return any(math.hypot(p[0] - m[0], p[1] - m[1]) < 4 * layout.radius for m, _ in layout.mouths)


def blind(layout: Layout, cue: Point, balls: dict[int, Point], on: Sequence[int]) -> list[Stroke]:
    """Straight at each ball on, whatever is in the way, full then half-ball either side:
    the last resort."""
    found = []
    for ball in on:
        u, d = _unit(cue, balls[ball])
        centre = math.atan2(u[1], u[0])
        half = math.asin(min(1.0, layout.radius / d))
        for angle in (centre, centre + half, centre - half):
            reach = min(d, 0.3)
            press = (cue[0] + math.cos(angle) * reach, cue[1] + math.sin(angle) * reach)
            found.append(Stroke(angle, _speed(d), press, ball, "blind"))
    return found


def choose(
    layout: Layout, cue: Point, balls: dict[int, Point], on: Sequence[int], attempt: int = 0
) -> Stroke:
    """The stroke to play: the `attempt`-th of pots, hits, cushions and blind strokes."""
    strokes = [
        *pots(layout, cue, balls, on),
        *hits(layout, cue, balls, on),
        *cushions(layout, cue, balls, on),
        *blind(layout, cue, balls, on),
    ]
    return strokes[attempt % len(strokes)]


def in_d_spots(layout: Layout, balls: dict[int, Point]) -> list[Point]:
    """Free places for the cue ball in the D (on or behind the baulk line, within its
    radius), a grid a person might try."""
    (cx, cy), rad, r = layout.d_centre, layout.d_radius, layout.radius
    spots = []
    for i in range(0, 6):
        for j in range(-6, 7):
            x, y = cx - 0.04 - i * 0.045, cy + j * 0.045
            inside = math.hypot(x - cx, y - cy) < rad - 0.01
            free = all(math.hypot(x - bx, y - by) > 2.2 * r for bx, by in balls.values())
            if inside and free:
                spots.append((x, y))
    return spots


def place_in_d(layout: Layout, balls: dict[int, Point], on: Sequence[int]) -> Point:
    """Where to put the cue ball in hand: the spot in the D with the easiest pot, else
    one with a ball on in plain view, else the D's middle."""
    spots = in_d_spots(layout, balls)
    scored = [(s, p) for p in spots for s in _scored_pots(layout, p, balls, on)[:1]]
    if scored:
        return min(scored, key=lambda f: f[0][0])[1]
    for spot in spots:
        if hits(layout, spot, balls, on):
            return spot
    return spots[len(spots) // 2] if spots else (layout.d_centre[0] - 0.1, layout.d_centre[1])
