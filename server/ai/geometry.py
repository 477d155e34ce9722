"""Shot geometry without the engine: ghost-ball aim, blocked paths and a quick estimate of
how likely a pot is under a given aim error. The search uses it to pick which pots to
simulate and to score the position a shot leaves (the best next shot from there).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from server.engine import CUE, BallSet, Table

MAX_CUT = math.radians(78.0)  # thinner cuts are not tried
JAW_BONUS = 0.008  # m a ball may be off the clean window and still drop (measured loosely)
MIN_AIM_SIGMA = math.radians(0.2)  # position play plans with at least this aim error


@dataclass(frozen=True)
class Pockets:
    """The aim point, outward normal and mouth width of each pocket of a table."""

    aims: np.ndarray  # (P, 2)
    outward: np.ndarray  # (P, 2)
    mouths: np.ndarray  # (P,)


@lru_cache(maxsize=8)
def pockets_of(table: Table) -> Pockets:
    aims, outward, mouths = [], [], []
    for p in table.pockets:
        (ax, ay), (bx, by) = p.jaws
        aims.append(((ax + bx) / 2, (ay + by) / 2))
        outward.append(p.outward)
        mouths.append(math.hypot(bx - ax, by - ay))
    return Pockets(np.array(aims), np.array(outward), np.array(mouths))


@dataclass(frozen=True)
class PotOption:
    """A straight or cut pot: hit `target` so that it goes into `pocket`.

    angle: the cue direction (radians from +x) at the ghost ball. chance: the geometric
    estimate of the pot under the aim sigma it was computed with. d1: cue to ghost ball,
    d2: object ball to pocket (m); cut: the cut angle (radians).
    """

    target: int
    pocket: int
    angle: float
    chance: float
    d1: float
    d2: float
    cut: float


def _segment_distances(a: np.ndarray, b: np.ndarray, pts: np.ndarray) -> np.ndarray:
    """Distance from each of `pts` (M, 2) to each segment a->b, a and b (K, 2): (K, M)."""
    ab = b - a
    length2 = np.maximum(np.sum(ab * ab, axis=-1), 1e-12)
    ap = pts[None, :, :] - a[:, None, :]
    t = np.clip(np.sum(ap * ab[:, None, :], axis=-1) / length2[:, None], 0.0, 1.0)
    closest = a[:, None, :] + t[..., None] * ab[:, None, :]
    return np.sqrt(np.sum((pts[None, :, :] - closest) ** 2, axis=-1))


def erf(x: np.ndarray) -> np.ndarray:
    """The error function, elementwise (Abramowitz and Stegun 7.1.26, error < 2e-7)."""
    sign = np.sign(x)
    a = np.abs(x)
    t = 1.0 / (1.0 + 0.3275911 * a)
    poly = t * (
        0.254829592 + t * (-0.284496736 + t * (1.421413741 + t * (-1.453152027 + t * 1.061405429)))
    )
    return sign * (1.0 - poly * np.exp(-a * a))


def pot_options(
    table: Table,
    balls: BallSet,
    targets: list[int],
    aim_sigma: float,
    cue_xy: tuple[float, float] | None = None,
) -> list[PotOption]:
    """Every unblocked straight or cut pot of a ball of `targets`, best chance first.

    `cue_xy` puts the cue ball somewhere else (ball in hand) without copying the set.
    """
    arrays = _pot_arrays(table, balls, targets, aim_sigma, cue_xy)
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


def _pot_arrays(
    table: Table,
    balls: BallSet,
    targets: list[int],
    aim_sigma: float,
    cue_xy: tuple[float, float] | None,
) -> (
    tuple[list[int], np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray] | None
):
    """(targets present, feasible, chance, cue angle, d1, d2, cos cut), each (T, P)."""
    on = balls.on_table
    ids = balls.ids
    want = [t for t in targets if t != CUE]
    if not want:
        return None
    present = set(ids[on].tolist())
    want = [t for t in want if t in present]
    rows = [int(np.flatnonzero(ids == t)[0]) for t in want]
    if not rows:
        return None
    cue_row = int(np.flatnonzero(ids == CUE)[0])
    if cue_xy is None:
        if not on[cue_row]:
            return None
        cue = balls.positions[cue_row]
    else:
        cue = np.array(cue_xy, dtype=np.float64)
    r = table.ball_radius
    pk = pockets_of(table)
    obj = balls.positions[rows]  # (T, 2)
    n_t, n_p = len(rows), len(pk.aims)
    to_pocket = pk.aims[None, :, :] - obj[:, None, :]  # (T, P, 2)
    d2 = np.maximum(np.linalg.norm(to_pocket, axis=-1), 1e-9)
    u = to_pocket / d2[..., None]
    ghost = obj[:, None, :] - 2 * r * u
    to_ghost = ghost - cue
    d1 = np.maximum(np.linalg.norm(to_ghost, axis=-1), 1e-9)
    v = to_ghost / d1[..., None]
    cos_cut = np.sum(u * v, axis=-1)
    cos_in = np.sum(u * pk.outward[None, :, :], axis=-1)
    window = (pk.mouths[None, :] * np.clip(cos_in, 0.0, 1.0) - 2 * r) / 2 + JAW_BONUS
    ok = (cos_cut > math.cos(MAX_CUT)) & (window > 0.003) & (cos_in > 0.35)
    gx, gy = ghost[..., 0], ghost[..., 1]
    ok &= (gx >= r) & (gx <= table.length - r) & (gy >= r) & (gy <= table.width - r)
    # Blockers: any other ball on the table within a ball's width of either path.
    others_mask = on.copy()
    others_mask[cue_row] = False
    flat_ghost = ghost.reshape(-1, 2)
    flat_obj = np.repeat(obj, n_p, axis=0)
    flat_aims = np.tile(pk.aims, (n_t, 1))
    own_rows = np.repeat(np.array(rows), n_p)
    if others_mask.any():
        other_rows = np.flatnonzero(others_mask)
        pts = balls.positions[other_rows]
        not_self = other_rows[None, :] != own_rows[:, None]
        cue_path = _segment_distances(np.broadcast_to(cue, flat_ghost.shape), flat_ghost, pts)
        obj_path = _segment_distances(flat_obj, flat_aims, pts)
        blocked = ((cue_path < 2 * r) | (obj_path < 2 * r)) & not_self
        ok &= ~blocked.any(axis=1).reshape(n_t, n_p)
    sigma_obj = d1 * max(aim_sigma, 1e-6) / (2 * r * np.maximum(cos_cut, 0.05))
    eps = window / d2
    chance = erf(eps / (sigma_obj * math.sqrt(2.0)))
    chance = np.where(ok, chance, 0.0)
    angles = np.arctan2(to_ghost[..., 1], to_ghost[..., 0])
    return want, ok, chance, angles, d1, d2, cos_cut


def best_chance(
    table: Table,
    balls: BallSet,
    targets: list[int],
    aim_sigma: float,
    cue_xy: tuple[float, float] | None = None,
) -> float:
    """How good the best pot is from here: mostly the best option's chance, a little of
    the second's (a table with two ways on is easier to play)."""
    arrays = _pot_arrays(table, balls, targets, max(aim_sigma, MIN_AIM_SIGMA), cue_xy)
    if arrays is None:
        return 0.0
    flat = arrays[2].ravel()
    if len(flat) == 1:
        return float(flat[0]) * 0.9
    top = np.partition(flat, len(flat) - 2)[-2:]
    return float(0.9 * top[1] + 0.1 * top[0])


def speed_for(option: PotOption, u_roll_g: float = 0.0981) -> float:
    """The cue-ball speed that just gets the object ball to the pocket, with a margin."""
    v_obj = math.sqrt(2 * u_roll_g * (option.d2 + 0.25))
    v_hit = v_obj / max(math.cos(option.cut), 0.25) / 0.95
    return math.sqrt(v_hit * v_hit + 2 * u_roll_g * option.d1) / 0.7


def open_share(table: Table, balls: BallSet, targets: list[int]) -> float:
    """The share of `targets` on the table that have a clear path to some pocket from where
    they lie (a ball in a cluster or behind others has none): how open the table is."""
    on = balls.on_table
    ids = balls.ids
    present = set(ids[on].tolist())
    rows = [int(np.flatnonzero(ids == t)[0]) for t in targets if t != CUE and t in present]
    if not rows:
        return 1.0
    r = table.ball_radius
    pk = pockets_of(table)
    obj = balls.positions[rows]
    n_t, n_p = len(rows), len(pk.aims)
    to_pocket = pk.aims[None, :, :] - obj[:, None, :]
    d2 = np.maximum(np.linalg.norm(to_pocket, axis=-1), 1e-9)
    cos_in = np.sum((to_pocket / d2[..., None]) * pk.outward[None, :, :], axis=-1)
    ok = cos_in > 0.45
    cue_row = int(np.flatnonzero(ids == CUE)[0])
    mask = on.copy()
    mask[cue_row] = False
    other_rows = np.flatnonzero(mask)
    if len(other_rows):
        pts = balls.positions[other_rows]
        own = np.repeat(np.array(rows), n_p)
        dist = _segment_distances(np.repeat(obj, n_p, axis=0), np.tile(pk.aims, (n_t, 1)), pts)
        blocked = (dist < 2 * r) & (other_rows[None, :] != own[:, None])
        ok &= ~blocked.any(axis=1).reshape(n_t, n_p)
    return float(np.mean(ok.any(axis=1)))
