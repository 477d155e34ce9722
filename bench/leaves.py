"""What a kept table is worth in a runout: the tables the top level keeps in `bench.ai`'s
runouts, by the balls it has left to pot and the chance of its best next pot, with the share
of them from which it went on to clear the rack.

    python -m bench.leaves [--racks 200] [--seed 5800] [--jobs 2]

Each kept table is described as the search's quick estimate sees it (`Search.value_of`):
`q`, the best next pot's chance (`Search.chance_for`), and `open`, how open the own balls
are (`geometry.open_share`). Printed: the share cleared by balls left and band of `q`, and
logistic fits of "cleared" on those parts, each fitted on the racks of odd seeds and scored
(log-loss per table) on the even ones and the other way round: the search's own blend
(`quality`, 0.55 q + 0.45 open), `q` and `open` apart, and with weights by balls left.
"""

from __future__ import annotations

import argparse
import itertools
import sys
from dataclasses import dataclass

import numpy as np

from bench.ai import _map, balls_to_pot, runout
from server.ai.geometry import open_share
from server.ai.levels import BY_NAME, LEVELS
from server.ai.search import OPEN_WEIGHT, Search
from server.rules import Game

BANDS = (0.0, 0.5, 0.8, 0.95, 1.01)  # of the best next pot's chance
LEFT_ROWS = ((1, 1), (2, 2), (3, 3), (4, 5), (6, 15))  # balls left to pot, the 8 counted
LEFT_CLASSES = ((1, 2), (3, 3), (4, 15))  # the weights of the last fit, by balls left
NO_DRAWS = np.zeros((0, 4))  # the search only values tables here: it simulates nothing


@dataclass(frozen=True)
class Kept:
    """A table the top level kept: its rack's seed, the balls left to pot (the 8 counted),
    the best next pot's chance, how open the own balls are, and whether the rack was
    then cleared."""

    seed: int
    left: int
    q: float
    open: float
    cleared: bool


def kept_tables(seed: int) -> list[Kept]:
    """The tables kept in the runout of rack `seed` (`bench.ai.runout`), as the search's
    quick estimate sees them."""
    level = BY_NAME[LEVELS[-1]]
    seen: list[tuple[int, float, float]] = []

    def look(game: Game) -> None:
        pos = game.position()
        search = Search(game.table, game.rules, pos, 1, level, NO_DRAWS, NO_DRAWS)
        q = search.chance_for(pos, game.balls)
        spread = open_share(game.table, game.balls, search.targets(pos))
        seen.append((balls_to_pot(game, 1), q, spread))

    cleared, _ = runout(seed, kept=look)
    return [Kept(seed, left, q, spread, cleared) for left, q, spread in seen]


def logistic_fit(x: np.ndarray, y: np.ndarray, ridge: float = 0.1) -> np.ndarray:
    """The weights (intercept first) of a logistic regression of `y` (0 or 1) on the columns
    of `x`, by Newton's method; `ridge` keeps a column that separates the data finite."""
    design = np.column_stack([np.ones(len(y)), x])
    w = np.zeros(design.shape[1])
    for _ in range(50):
        p = 1.0 / (1.0 + np.exp(-design @ w))
        grad = design.T @ (p - y) + ridge * w
        hess = (design * (p * (1 - p))[:, None]).T @ design + ridge * np.eye(len(w))
        step = np.linalg.solve(hess, grad)
        w -= step
        if float(np.max(np.abs(step))) < 1e-10:
            break
    return w


def log_loss(x: np.ndarray, y: np.ndarray, w: np.ndarray) -> float:
    p = 1.0 / (1.0 + np.exp(-(w[0] + x @ w[1:])))
    p = np.clip(p, 1e-9, 1 - 1e-9)
    return float(-np.mean(y * np.log(p) + (1 - y) * np.log(1 - p)))


def held_out_loss(x: np.ndarray, y: np.ndarray, odd: np.ndarray) -> float:
    """Log-loss per table of a fit on one half of the racks, scored on the other, both ways."""
    if odd.all() or not odd.any():
        return float("nan")
    a = log_loss(x[~odd], y[~odd], logistic_fit(x[odd], y[odd]))
    b = log_loss(x[odd], y[odd], logistic_fit(x[~odd], y[~odd]))
    return (a + b) / 2


def models(kept: list[Kept]) -> dict[str, np.ndarray]:
    """The columns of each fit."""
    q = np.array([k.q for k in kept])
    spread = np.array([k.open for k in kept])
    left = np.array([k.left for k in kept], dtype=float)
    by_class = [left]
    for lo, hi in LEFT_CLASSES:
        inside = ((left >= lo) & (left <= hi)).astype(float)
        by_class += [inside * q, inside * spread]
    return {
        "constant": np.zeros((len(kept), 0)),
        "the search's quality": ((1 - OPEN_WEIGHT) * q + OPEN_WEIGHT * spread)[:, None],
        "q, open": np.column_stack([q, spread]),
        "q, open, balls left": np.column_stack([q, spread, left]),
        "balls left; q, open by 1-2 / 3 / 4+ left": np.column_stack(by_class),
    }


def report(kept: list[Kept]) -> None:
    cleared = np.array([k.cleared for k in kept], dtype=float)
    share = f"; cleared from them: {100 * cleared.mean():.1f} %" if kept else ""
    print(f"kept tables: {len(kept)}{share}")
    print("cleared from a kept table, by balls left to pot (the 8 counted) and the best next")
    print("pot's chance q (tables: share cleared):")
    heads = [f"q {lo:.2f}-{min(hi, 1.0):.2f}" for lo, hi in itertools.pairwise(BANDS)]
    print(f"  {'left':>5}  " + "".join(f"{h:>16}" for h in heads))
    for lo, hi in LEFT_ROWS:
        cells = []
        for a, b in itertools.pairwise(BANDS):
            inside = [k for k in kept if lo <= k.left <= hi and a <= k.q < b]
            rate = sum(k.cleared for k in inside) / len(inside) if inside else 0.0
            cells.append(f"{len(inside):>6}: {100 * rate:3.0f} %" if inside else f"{'-':>16}")
        label = f"{lo}" if lo == hi else f"{lo}-{hi}"
        print(f"  {label:>5}  " + "".join(f"{c:>16}" for c in cells))
    print("logistic fits of clearing (log-loss per table, fitted on odd seeds' racks and")
    print("scored on even ones', and the other way round; weights fitted on all):")
    odd = np.array([k.seed % 2 == 1 for k in kept])
    for name, x in models(kept).items():
        weights = " ".join(f"{w:+.2f}" for w in logistic_fit(x, cleared)) if kept else ""
        print(f"  {name:42s} {held_out_loss(x, cleared, odd):.4f}   weights {weights}")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--racks", type=int, default=200)
    parser.add_argument("--seed", type=int, default=5800, help="the first rack's seed")
    parser.add_argument("--jobs", type=int, default=1, help="worker processes")
    args = parser.parse_args(argv)
    seeds = list(range(args.seed, args.seed + args.racks))
    kept = [k for found in _map(kept_tables, seeds, args.jobs) for k in found]
    print(f"bench.leaves: racks {args.racks} from seed {args.seed}; jobs {args.jobs}")
    report(kept)
    return 0


if __name__ == "__main__":
    sys.exit(main())
