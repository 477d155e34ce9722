"""The computer at three-cushion: strokes searched with the engine, judged by how often they
score under the level's execution noise.

No geometry of its own: every candidate stroke is simulated (`settle`, some 0.05 ms on a
three-ball table) and judged by the rule itself (`carom_score.is_point` on the cue ball's
path). The grid: the cue ball sent at each object ball at a range of cuts (from a thin
hit on one side to a thin hit on the other) and in every direction round the table (the
strokes that meet cushions first), at a few speeds and tips. The strokes that score
exactly are ranked by how many of their neighbours in the grid score too (a wide window),
and the best few are played again under noise drawn from the level's arm (`perturb`): the
one that scores most often is played. With no stroke scoring often enough, the levels that
play safe weigh what a stroke leaves the opponent (`leave_value`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace

import numpy as np

from server.engine import BALL_RADIUS, BallSet, Shot, Table, settle
from server.engine.rack import RED, WHITE, YELLOW
from server.rules.carom_score import is_point
from server.rules.shotfacts import shot_facts

from .aiming import aimed, perturb
from .levels import Level


@dataclass(frozen=True)
class CaromEffort:
    """How much a level searches: cut steps across each object ball, directions round the
    table, the speeds (m/s) and tips (side, height) of each, how many exact points are
    played under noise (`keep`) and with how many draws (`samples`), and whether it weighs
    the leave when it cannot score (`defence`)."""

    cuts: int
    directions: int
    speeds: tuple[float, ...]
    tips: tuple[tuple[float, float], ...]
    keep: int
    samples: int
    defence: bool


_TIPS_FEW = ((0.0, 0.2), (0.3, 0.2), (-0.3, 0.2))
_TIPS_MORE = (*_TIPS_FEW, (0.4, -0.1), (-0.4, -0.1), (0.0, -0.3))
_TIPS_ALL = (*_TIPS_MORE, (0.2, 0.4), (-0.2, 0.4), (0.45, 0.1), (-0.45, 0.1))
EFFORT: dict[str, CaromEffort] = {
    "beginner": CaromEffort(9, 24, (3.0, 4.5), _TIPS_FEW[:1], 2, 4, False),
    "amateur": CaromEffort(15, 48, (2.5, 3.5, 5.0), _TIPS_FEW, 4, 8, False),
    "club": CaromEffort(25, 90, (2.5, 3.5, 4.5, 6.0), _TIPS_MORE, 8, 16, True),
    "pro": CaromEffort(41, 120, (2.2, 3.0, 3.8, 4.8, 6.0), _TIPS_ALL, 14, 30, True),
}
PLAY_SAFE_BELOW = 0.25  # a best chance under this weighs the leave too
LEAVE_WEIGHT = 0.3


@dataclass
class CaromStroke:
    """A stroke of the grid and what the search found: `first` the ball it is sent at
    (None for a direction round the table), `cell` its place in the grid (for its
    neighbours), `point` whether it scores exactly, `rate` how often under noise, `leave`
    the leave's value for the opponent (lower is better for us)."""

    shot: Shot
    first: int | None
    cell: tuple[int, int, int, int]
    point: bool = False
    rate: float = 0.0
    leave: float = 0.0
    support: int = 0


@dataclass(frozen=True)
class CaromPlan:
    """The stroke chosen, its chance under noise, whether it is a safety, and the
    simulations it took."""

    shot: Shot
    chance: float
    first: int | None
    safety: bool
    sims: int


def carom_level(level: Level, table: Table) -> Level:
    """`level` with its tip error in this table's ball radii (the levels give it in mm)."""
    return replace(level, tip_mm=level.tip_mm * table.ball_radius / BALL_RADIUS)


class CaromSearch:
    """One turn's search from `balls`, striking `cue` (module docstring)."""

    def __init__(
        self,
        table: Table,
        balls: BallSet,
        cue: int,
        level: Level,
        rng: np.random.Generator,
    ) -> None:
        self.table, self.balls, self.cue = table, balls, cue
        self.level = carom_level(level, table)
        self.effort = EFFORT[level.name]
        self.noise = rng.standard_normal((self.effort.samples, 4))
        self.others = [b for b in (WHITE, YELLOW, RED) if b != cue]
        self.sims = 0

    def plan(self, first_only: int | None = None) -> CaromPlan:
        """The stroke to play (`first_only`: the opening stroke must meet that ball first)."""
        strokes = self.grid(first_only)
        for stroke in strokes:
            stroke.point = self.scores(stroke.shot, first_only)
        _support(strokes)
        points = sorted((s for s in strokes if s.point), key=lambda s: -s.support)
        chosen = points[: self.effort.keep]
        for stroke in chosen:
            stroke.rate = self.rate(stroke.shot, first_only)
        best = max(chosen, key=lambda s: s.rate, default=None)
        if best is not None and (best.rate >= PLAY_SAFE_BELOW or not self.effort.defence):
            return CaromPlan(best.shot, best.rate, best.first, False, self.sims)
        return self.safe_or_best(strokes, best)

    def grid(self, first_only: int | None) -> list[CaromStroke]:
        """Every stroke of the level's grid (at the balls, and round the table)."""
        e = self.effort
        cx, cy = self.balls.position_of(self.cue)
        lines: list[tuple[float, int | None, int]] = []
        targets = [first_only] if first_only is not None else self.others
        for ball in targets:
            bx, by = self.balls.position_of(ball)
            dist = math.hypot(bx - cx, by - cy)
            base = math.atan2(by - cy, bx - cx)
            reach = 2 * self.table.ball_radius
            for k, f in enumerate(np.linspace(-0.95, 0.95, e.cuts)):
                offset = max(-1.0, min(f * reach / max(dist, 1e-9), 1.0))
                lines.append((base + math.asin(offset), ball, k))
        if first_only is None:
            for k in range(e.directions):
                lines.append((2 * math.pi * k / e.directions, None, k))
        out = []
        for angle, first, k in lines:
            for i, speed in enumerate(e.speeds):
                for j, (side, height) in enumerate(e.tips):
                    shot = replace(aimed(angle, speed, side, height), ball=self.cue)
                    group = -1 if first is None else first
                    out.append(CaromStroke(shot, first, (group, k, i, j)))
        return out

    def path(self, shot: Shot) -> tuple[int, ...]:
        """What the cue ball meets on `shot`, in order (a cushion is -1)."""
        self.sims += 1
        return shot_facts(self.balls, settle(self.table, self.balls, shot), self.cue).cue_path

    def scores(self, shot: Shot, first_only: int | None) -> bool:
        path = self.path(shot)
        if first_only is not None and (not path or path[0] != first_only):
            return False
        return is_point(path, self.cue)

    def rate(self, shot: Shot, first_only: int | None) -> float:
        """The share of the level's noisy draws of `shot` that score."""
        made = sum(self.scores(perturb(shot, row, self.level), first_only) for row in self.noise)
        return made / max(len(self.noise), 1)

    def safe_or_best(self, strokes: Sequence[CaromStroke], best: CaromStroke | None) -> CaromPlan:
        """The point that scores most often, weighed against what each stroke leaves the
        opponent (`leave_value`), among the points and the strokes that meet both balls."""
        pool = sorted(
            (s for s in strokes if s.point or s.first is not None),
            key=lambda s: -(s.rate + s.support * 0.01),
        )[: self.effort.keep * 2]
        scored: list[tuple[float, CaromStroke]] = []
        for stroke in pool:
            if not stroke.point:
                stroke.rate = 0.0
            final = settle(self.table, self.balls, stroke.shot).final
            self.sims += 1
            stroke.leave = leave_value(self.table, final, self.cue)
            scored.append((stroke.rate - LEAVE_WEIGHT * (1 - stroke.rate) * stroke.leave, stroke))
        if not scored:
            fallback = best or strokes[0]
            return CaromPlan(fallback.shot, fallback.rate, fallback.first, True, self.sims)
        _, chosen = max(scored, key=lambda vs: vs[0])
        safety = chosen.rate < PLAY_SAFE_BELOW
        return CaromPlan(chosen.shot, chosen.rate, chosen.first, safety, self.sims)


def _support(strokes: Sequence[CaromStroke]) -> None:
    """Each scoring stroke's count of scoring neighbours (next cut or direction, same speed
    and tip; the next speed, same line and tip): a wide window survives the arm's error."""
    scoring = {s.cell for s in strokes if s.point}
    for s in strokes:
        if not s.point:
            continue
        g, k, i, j = s.cell
        near = ((g, k - 1, i, j), (g, k + 1, i, j), (g, k, i - 1, j), (g, k, i + 1, j))
        s.support = sum(c in scoring for c in near)


def leave_value(table: Table, balls: BallSet, cue: int) -> float:
    """How much the table left is worth to the opponent, 0 to 1: their cue ball's two
    object balls close together is easy, far apart and their ball on a cushion hard."""
    theirs = YELLOW if cue == WHITE else WHITE
    tx, ty = balls.position_of(theirs)
    a, b = (balls.position_of(x) for x in (cue, RED))
    spread = math.dist(a, b) / math.hypot(table.length, table.width)
    rail = min(tx, ty, table.length - tx, table.width - ty) / (table.width / 2)
    return float(0.6 * (1.0 - spread) + 0.4 * min(rail, 1.0))
