"""Shot geometry without the engine: ghost-ball aim, blocked paths and a quick estimate of
how likely a pot is under a given aim error. The search uses it to pick which pots to
simulate and to score the position a shot leaves (the best next shot from there).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from server.engine import CUE, BallSet, Table

MAX_CUT = math.radians(78.0)  # thinner cuts are not tried
MIN_AIM_SIGMA = math.radians(0.2)  # position play plans with at least this aim error
# How open a ball is (`open_share`): its best pot from a cue ball this far behind the ghost
# ball, straight or cut by one of these angles; a chance of OPEN_EASY counts as fully open.
OPEN_REACH = 0.3
OPEN_CUTS = np.radians(np.array([0.0, 15.0, -15.0, 30.0, -30.0, 45.0, -45.0]))
OPEN_EASY = 0.5
GEOMETRIC_JAW = 0.008  # m the plain estimate widens a mouth's clean window by


@dataclass(frozen=True)
class ChanceModel:
    """How the pot chance's object-ball angle error is built from the aim sigma.

    The object ball leaves at an error of sigma_obj = sqrt((aim_scale * d1 * sigma_aim /
    (2R cos cut))^2 + floor^2 + (cut * sin cut)^2) radians, against the mouth's clean window
    widened by `jaw` metres (narrowed by `side` metres for a side pocket). `floor` and `cut`
    are what the tip error (squirt, throw) adds whatever the distance; measured at the
    FastFiz noise and scaled by the level's tip sigma.
    """

    aim_scale: float = 1.0
    floor: float = 0.0
    cut: float = 0.0
    jaw: float = GEOMETRIC_JAW
    side: float = 0.0


GEOMETRIC = ChanceModel()  # the plain ghost-ball estimate (the lower levels plan with it)
# Fitted (maximum likelihood over a grid, `python -m bench.ai --only calibrate --configs 3000
# --seed 11 --fit`) to 3,000 random pots of one ball played with the pro's FastFiz noise,
# aimed for the throw as the search aims (at the pocket's window, as the pro aims: refitted
# so, it gives the same point), 30 noisy strokes each. The
# plain model ignores that a long object-ball distance costs far more than a long cue-ball
# one. The earlier fit (to pots aimed at the ghost ball) had a floor of 1.4 degrees,
# several times what the object ball strays by from a cue ball 0.2 m away (0.35-0.53
# degrees in the engine): it made a long object-ball distance hard however close the cue
# ball was, and ordered the likely pots worse than the plain model did (docs/ai.md, item 7
# of "How the search works").
FASTFIZ = ChanceModel(aim_scale=2.0, floor=0.015, cut=0.04, jaw=0.032, side=0.02)
FASTFIZ_TIP_MM = 0.5


@dataclass(frozen=True)
class Pockets:
    """The aim point, outward normal and mouth width of each pocket of a table."""

    aims: np.ndarray  # (P, 2)
    outward: np.ndarray  # (P, 2)
    mouths: np.ndarray  # (P,)
    side: np.ndarray  # (P,) 1.0 for a side pocket, else 0.0


_pockets: dict[int, tuple[Table, Pockets]] = {}


def pockets_of(table: Table) -> Pockets:
    """The table's pockets as arrays, built once per table (looked up by identity: hashing
    a `Table` walks all its fields, and the search asks for every simulated outcome)."""
    cached = _pockets.get(id(table))
    if cached is not None and cached[0] is table:
        return cached[1]
    pockets = _build_pockets(table)
    if len(_pockets) > 16:
        _pockets.clear()
    _pockets[id(table)] = (table, pockets)
    return pockets


def _build_pockets(table: Table) -> Pockets:
    aims, outward, mouths = [], [], []
    for p in table.pockets:
        (ax, ay), (bx, by) = p.jaws
        aims.append(((ax + bx) / 2, (ay + by) / 2))
        outward.append(p.outward)
        mouths.append(math.hypot(bx - ax, by - ay))
    side = [1.0 if abs(o[0]) < 0.1 else 0.0 for o in outward]
    return Pockets(np.array(aims), np.array(outward), np.array(mouths), np.array(side))


@dataclass(frozen=True)
class PotOption:
    """A straight or cut pot: hit `target` so that it goes into `pocket`.

    angle: the cue direction (radians from +x) at the ghost ball. chance: the geometric
    estimate of the pot under the aim sigma it was computed with. d1: cue to ghost ball,
    d2: object ball to pocket (m); cut: the cut angle (radians) on the ball the cue ball
    hits. via: "direct", "bank" (d2 is then the path off the cushion), "combo" (the cue
    ball hits `carrier`, which travels `link` to hit `target` at a cut of `link_cut`),
    "carom" (`target` travels `link` to glance off `carrier`, its path turning by
    `link_cut`; d2 is then from the kiss to the pocket) or "billiard" (the cue ball
    glances off `carrier` at a cut of `cut` and travels `link` to hit `target` at a cut of
    `link_cut`); `indirect`. route: the aims of one bank route share it (one for each
    restitution the cushion may have).
    """

    target: int
    pocket: int
    angle: float
    chance: float
    d1: float
    d2: float
    cut: float
    via: str = "direct"
    carrier: int | None = None
    link: float = 0.0
    link_cut: float = 0.0
    route: int = 0


@njit(cache=True, inline="always")
def _near_segment(ax: float, ay: float, bx: float, by: float, px: float, py: float) -> float:
    """Distance from the point p to the segment a->b."""
    abx, aby = bx - ax, by - ay
    length2 = max(abx * abx + aby * aby, 1e-12)
    t = min(max(((px - ax) * abx + (py - ay) * aby) / length2, 0.0), 1.0)
    dx, dy = px - (ax + t * abx), py - (ay + t * aby)
    return math.sqrt(dx * dx + dy * dy)


@njit(cache=True, inline="always")
def path_clear(
    ax: float,
    ay: float,
    bx: float,
    by: float,
    positions: np.ndarray,
    on: np.ndarray,
    skip_a: int,
    skip_b: int,
    r: float,
) -> bool:
    """Whether no ball on the table but rows `skip_a` and `skip_b` (the balls that travel
    it) lies within a ball's width of the path a->b."""
    for k in range(len(positions)):
        if not on[k] or k == skip_a or k == skip_b:  # noqa: SIM109 (numba)
            continue
        if _near_segment(ax, ay, bx, by, positions[k, 0], positions[k, 1]) < 2 * r:
            return False
    return True


@njit(cache=True, inline="always")
def clean_window(mouth: float, cos_in: float, r: float, jaw: float) -> float:
    """Half the lateral room a ball has to drop through a mouth of width `mouth` that it
    approaches at `cos_in` to the pocket's normal, widened by `jaw`."""
    return (mouth * min(max(cos_in, 0.0), 1.0) - 2 * r) / 2 + jaw


@njit(cache=True, inline="always")
def drop_chance(window: float, dist2: float, sigma_obj: float) -> float:
    """The chance a ball sent `dist2` to the pocket with an angle error of `sigma_obj`
    (normal, radians) stays within `window` of the mouth's centre."""
    return math.erf((window / dist2) / (sigma_obj * math.sqrt(2.0)))


@njit(cache=True, inline="always")
def ghost_error(dist: float, aim_sigma: float, cos_cut: float, r: float, scale: float) -> float:
    """The angle error of a struck ball from the striking ball's direction error
    `aim_sigma` over `dist` to the contact (the cue ball's to the ghost ball, or a first
    object ball's to the second in a combination or a kiss): the contact moves by
    dist * sigma across the ball's width seen at the cut (2R cos cut), times `scale` (the
    chance model's aim scale, 1 for the plain one)."""
    return scale * dist * aim_sigma / (2 * r * max(cos_cut, 0.05))


@njit(cache=True, inline="always")
def object_sigma(
    s_aim: float, sin_cut: float, floor: float, cut_sigma: float, extra: float
) -> float:
    """The object ball's angle error (`ChanceModel`): the aim term `s_aim` (scaled), the
    floor and the cut term the tip error adds, and `extra` (a cushion's scatter), as one
    sigma."""
    s_cut = cut_sigma * sin_cut
    return math.sqrt(s_aim * s_aim + floor * floor + s_cut * s_cut + extra * extra)


@njit(cache=True)
def _pot_kernel(
    positions: np.ndarray,
    on: np.ndarray,
    rows: np.ndarray,
    cue_row: int,
    cue_x: float,
    cue_y: float,
    aims: np.ndarray,
    outward: np.ndarray,
    mouths: np.ndarray,
    side: np.ndarray,
    r: float,
    length: float,
    width: float,
    aim_sigma: float,
    model: tuple[float, float, float, float, float],
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(feasible, chance, cue angle, d1, d2, cos cut), each (T, P), for the balls `rows`:
    ghost-ball aim at each pocket's mouth, rejected when too thin a cut, too steep an
    approach, a ghost ball off the bed or any ball within a ball's width of either path;
    the chance is that of the object ball's angle error against the mouth's clean window.
    Compiled: the search calls it for every simulated outcome (the table it leaves)."""
    n_t, n_p = len(rows), len(aims)
    ok = np.zeros((n_t, n_p), dtype=np.bool_)
    chance = np.zeros((n_t, n_p))
    angle = np.zeros((n_t, n_p))
    d1 = np.zeros((n_t, n_p))
    d2 = np.zeros((n_t, n_p))
    cos_cut = np.zeros((n_t, n_p))
    min_cos = math.cos(MAX_CUT)
    sigma = max(aim_sigma, 1e-6)
    aim_scale, floor, cut_sigma, jaw, side_cost = model
    for i in range(n_t):
        row = rows[i]
        ox, oy = positions[row, 0], positions[row, 1]
        for p in range(n_p):
            tx, ty = aims[p, 0] - ox, aims[p, 1] - oy
            dist2 = max(math.sqrt(tx * tx + ty * ty), 1e-9)
            ux, uy = tx / dist2, ty / dist2
            gx, gy = ox - 2 * r * ux, oy - 2 * r * uy
            vx, vy = gx - cue_x, gy - cue_y
            dist1 = max(math.sqrt(vx * vx + vy * vy), 1e-9)
            cc = (ux * vx + uy * vy) / dist1
            cos_in = ux * outward[p, 0] + uy * outward[p, 1]
            window = clean_window(mouths[p], cos_in, r, jaw) - side_cost * side[p]
            d1[i, p], d2[i, p], cos_cut[i, p] = dist1, dist2, cc
            angle[i, p] = math.atan2(vy, vx)
            if cc <= min_cos or window <= 0.003 or cos_in <= 0.35:
                continue
            if gx < r or gx > length - r or gy < r or gy > width - r:
                continue
            if not (
                path_clear(cue_x, cue_y, gx, gy, positions, on, cue_row, row, r)
                and path_clear(ox, oy, aims[p, 0], aims[p, 1], positions, on, cue_row, row, r)
            ):
                continue
            ok[i, p] = True
            s_aim = ghost_error(dist1, sigma, cc, r, aim_scale)
            sin_cut = math.sqrt(max(1.0 - cc * cc, 0.0))
            sigma_obj = object_sigma(s_aim, sin_cut, floor, cut_sigma, 0.0)
            chance[i, p] = drop_chance(window, dist2, sigma_obj)
    return ok, chance, angle, d1, d2, cos_cut


@njit(cache=True)
def _open_kernel(
    positions: np.ndarray,
    on: np.ndarray,
    rows: np.ndarray,
    cue_row: int,
    aims: np.ndarray,
    outward: np.ndarray,
    mouths: np.ndarray,
    r: float,
    length: float,
    width: float,
    sigma: float,
    cuts: np.ndarray,
) -> float:
    """How pottable the balls `rows` are, on average: each counts by its best pot from a
    cue ball placed `OPEN_REACH` behind the ghost ball (straight or at one of `cuts`),
    on the bed with a clear path to it, and by a clear path to the pocket; a chance of
    `OPEN_EASY` or more counts in full."""
    total = 0.0
    for i in range(len(rows)):
        row = rows[i]
        ox, oy = positions[row, 0], positions[row, 1]
        best = 0.0
        for p in range(len(aims)):
            tx, ty = aims[p, 0] - ox, aims[p, 1] - oy
            dist2 = max(math.sqrt(tx * tx + ty * ty), 1e-9)
            ux, uy = tx / dist2, ty / dist2
            cos_in = ux * outward[p, 0] + uy * outward[p, 1]
            window = clean_window(mouths[p], cos_in, r, GEOMETRIC_JAW)
            if cos_in <= 0.35 or window <= 0.003:
                continue
            if not path_clear(ox, oy, aims[p, 0], aims[p, 1], positions, on, cue_row, row, r):
                continue
            gx, gy = ox - 2 * r * ux, oy - 2 * r * uy
            for c in range(len(cuts)):
                cos_c, sin_c = math.cos(cuts[c]), math.sin(cuts[c])
                vx, vy = ux * cos_c - uy * sin_c, ux * sin_c + uy * cos_c  # the approach
                cx, cy = gx - OPEN_REACH * vx, gy - OPEN_REACH * vy
                if cx < r or cx > length - r or cy < r or cy > width - r:
                    continue
                if not path_clear(cx, cy, gx, gy, positions, on, cue_row, row, r):
                    continue
                s_aim = ghost_error(OPEN_REACH, sigma, cos_c, r, 1.0)
                best = max(best, drop_chance(window, dist2, s_aim))
        total += min(best / OPEN_EASY, 1.0)
    return total / len(rows)


def pot_options(
    table: Table,
    balls: BallSet,
    targets: list[int],
    aim_sigma: float,
    cue_xy: tuple[float, float] | None = None,
    model: ChanceModel = GEOMETRIC,
) -> list[PotOption]:
    """Every unblocked straight or cut pot of a ball of `targets`, best chance first.

    `cue_xy` puts the cue ball somewhere else (ball in hand) without copying the set.
    """
    arrays = _pot_arrays(table, balls, targets, aim_sigma, cue_xy, model)
    if arrays is None:
        return []
    want, ok, chance, angles, d1, d2, cos_cut = arrays
    out = []
    for ti, pi in zip(*np.nonzero(ok), strict=True):
        out.append(
            PotOption(
                target=want[ti],
                pocket=int(pi),
                angle=float(angles[ti, pi]),
                chance=float(chance[ti, pi]),
                d1=float(d1[ti, pi]),
                d2=float(d2[ti, pi]),
                cut=float(math.acos(min(1.0, float(cos_cut[ti, pi])))),
            )
        )
    out.sort(key=lambda o: -o.chance)
    return out


def _rows_of(balls: BallSet, targets: list[int]) -> tuple[list[int], np.ndarray, int]:
    """(targets on the table, their rows, the cue ball's row)."""
    ids = balls.ids.tolist()
    on = balls.on_table
    row_of = {b: i for i, b in enumerate(ids)}
    want = [t for t in targets if t != CUE and t in row_of and on[row_of[t]]]
    return want, np.array([row_of[t] for t in want], dtype=np.int64), row_of[CUE]


def _pot_arrays(
    table: Table,
    balls: BallSet,
    targets: list[int],
    aim_sigma: float,
    cue_xy: tuple[float, float] | None,
    model: ChanceModel = GEOMETRIC,
) -> (
    tuple[list[int], np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray] | None
):
    """(targets present, feasible, chance, cue angle, d1, d2, cos cut), each (T, P)."""
    want, rows, cue_row = _rows_of(balls, targets)
    if not want:
        return None
    on = balls.on_table
    if cue_xy is None:
        if not on[cue_row]:
            return None
        cue_x, cue_y = float(balls.positions[cue_row, 0]), float(balls.positions[cue_row, 1])
    else:
        cue_x, cue_y = float(cue_xy[0]), float(cue_xy[1])
    pk = pockets_of(table)
    ok, chance, angles, d1, d2, cos_cut = _pot_kernel(
        balls.positions,
        on,
        rows,
        cue_row,
        cue_x,
        cue_y,
        pk.aims,
        pk.outward,
        pk.mouths,
        pk.side,
        float(table.ball_radius),
        float(table.length),
        float(table.width),
        float(aim_sigma),
        (model.aim_scale, model.floor, model.cut, model.jaw, model.side),
    )
    return want, ok, chance, angles, d1, d2, cos_cut


def best_chance(
    table: Table,
    balls: BallSet,
    targets: list[int],
    aim_sigma: float,
    cue_xy: tuple[float, float] | None = None,
    model: ChanceModel = GEOMETRIC,
) -> float:
    """How good the best pot is from here: mostly the best option's chance, a little of
    the second's (a table with two ways on is easier to play)."""
    if model is GEOMETRIC:
        aim_sigma = max(aim_sigma, MIN_AIM_SIGMA)
    arrays = _pot_arrays(table, balls, targets, aim_sigma, cue_xy, model)
    if arrays is None:
        return 0.0
    flat = arrays[2].ravel()
    if len(flat) == 1:
        return float(flat[0]) * 0.9
    top = np.partition(flat, len(flat) - 2)[-2:]
    return float(0.9 * top[1] + 0.1 * top[0])


def speed_for(option: PotOption, u_roll_g: float = 0.0981) -> float:
    """The cue-ball speed that just gets the object ball to the pocket, with a margin.

    The last factor is measured with the engine (the least speed that drops straight and
    cut pots): the object ball slides before it rolls, so a long one needs more than
    rolling friction alone says (x1.13 at 0.8 m, x1.3 at 1.5 m). A bank loses some of its
    pace at the cushion; a combination's first ball must bring the second its speed, a
    carom's ball keeps only the share of its speed along the tangent of the kiss, and so
    does a billiard's cue ball after its glance."""
    v_obj = math.sqrt(2 * u_roll_g * (option.d2 + 0.25))
    if option.via == "bank":
        v_obj /= 0.85  # the cushion takes some of it
    if option.via in ("combo", "carom", "billiard"):  # the second collision's speed, and the link
        v_obj = math.sqrt(
            (v_obj / max(math.cos(option.link_cut), 0.25) / 0.95) ** 2 + 2 * u_roll_g * option.link
        )
    if option.via == "billiard":  # the cue ball keeps the sine of the glance's cut
        v_hit = v_obj / max(math.sin(option.cut), 0.25) / 0.95
    else:
        v_hit = v_obj / max(math.cos(option.cut), 0.25) / 0.95
    slide = 1.0 + 0.25 * max(option.d2 - 0.3, 0.0)
    return math.sqrt(v_hit * v_hit + 2 * u_roll_g * option.d1) / 0.7 * slide


def open_share(table: Table, balls: BallSet, targets: list[int]) -> float:
    """How open the table is for `targets`, from 0 to 1: each ball on the table counts by
    how pottable it is from a cue ball placed well for it (`_open_kernel`). A ball in a
    cluster, behind others, or whose only clear line to a pocket needs the cue ball off
    the bed or behind other balls (frozen on a rail beside an opponent's ball) counts
    little; a clear path alone counted such a ball as open."""
    want, rows, cue_row = _rows_of(balls, targets)
    if not want:
        return 1.0
    pk = pockets_of(table)
    return float(
        _open_kernel(
            balls.positions,
            balls.on_table,
            rows,
            cue_row,
            pk.aims,
            pk.outward,
            pk.mouths,
            float(table.ball_radius),
            float(table.length),
            float(table.width),
            MIN_AIM_SIGMA,
            OPEN_CUTS,
        )
    )
