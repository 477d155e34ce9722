"""How well the computer's caroms and billiards are aimed: the share of exact strokes that
drop on the geometry's aim and on the aim the engine corrects, and how often they drop under
the top level's execution noise against the chance the geometry gave them.

    python -m bench.caroms --tables 200 --seed 0
    python -m bench.caroms --tables 1000 --seed 0 --kind billiard

Random tables of eleven balls; on each, the best `--routes` caroms of the balls 1-5 (as
`indirect.carom_options` ranks them: a ball 1-5 glances off another ball into a pocket), or
with `--kind billiard` the best billiards (`indirect.billiard_options`: the cue ball glances
off a ball 1-5 into another of them), each at the search's three carom speeds.
"""

from __future__ import annotations

import argparse
import math
import sys
import time

import numpy as np

from server.ai import LEVELS, Bot
from server.ai.aiming import aim_carom, aimed, perturb
from server.ai.geometry import speed_for
from server.ai.indirect import billiard_options, carom_options
from server.ai.search import CAROM_SPEED_FACTORS
from server.engine import MAX_SPEED, BallSet, Shot, Table, simulate

BALLS = (0, 1, 2, 3, 4, 5, 8, 9, 10, 11, 12)
TARGETS = [1, 2, 3, 4, 5]
TRIALS = 20  # noisy strokes per corrected carom that drops without noise
BINS = (0.0, 0.2, 0.4, 0.6, 0.8, 1.01)


def random_table(table: Table, rng: np.random.Generator) -> BallSet:
    """`BALLS` anywhere on the bed, none touching."""
    r = table.ball_radius
    spots: dict[int, tuple[float, float]] = {}
    for ball in BALLS:
        while True:
            spot = (rng.uniform(r, table.length - r), rng.uniform(r, table.width - r))
            if all(math.dist(spot, other) > 2.05 * r for other in spots.values()):
                spots[ball] = spot
                break
    return BallSet.place(spots)


def drops(table: Table, balls: BallSet, shot: Shot, target: int) -> bool:
    final = simulate(table, balls, shot).final
    return not final.on_table[final.index(target)]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--tables", type=int, default=200)
    parser.add_argument("--routes", type=int, default=2, help="best caroms tried per table")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--kind", choices=("carom", "billiard"), default="carom")
    args = parser.parse_args(argv)
    table = Table.pool("9ft")
    level = Bot(LEVELS[-1]).level
    rng = np.random.default_rng(args.seed)
    noise = rng.standard_normal((TRIALS, 4))
    t0 = time.process_time()
    strokes, sims, raw_made, fixed_made = 0, 0, 0, 0
    by_chance: dict[int, list[float]] = {k: [] for k in range(len(BINS) - 1)}
    for _ in range(args.tables):
        balls = random_table(table, rng)
        if args.kind == "carom":
            options = carom_options(table, balls, TARGETS, level.aim)
        else:
            options = billiard_options(table, balls, TARGETS, TARGETS, level.aim)
        for option in options[: args.routes]:
            first = option.carrier if args.kind == "billiard" else None
            for factor in CAROM_SPEED_FACTORS:
                speed = min(speed_for(option) * factor, 0.85 * MAX_SPEED)
                shot = aimed(option.angle, speed, 0.0, 0.0)
                fixed, used = aim_carom(table, balls, shot, option.target, option.pocket, first)
                strokes, sims = strokes + 1, sims + used
                raw_made += drops(table, balls, shot, option.target)
                if not drops(table, balls, fixed, option.target):
                    continue
                fixed_made += 1
                rate = np.mean(
                    [drops(table, balls, perturb(fixed, n, level), option.target) for n in noise]
                )
                by_chance[int(np.digitize(option.chance, BINS)) - 1].append(float(rate))
    print(
        f"{args.kind}s on {args.tables} random tables (seed {args.seed}): {strokes} strokes, "
        f"{time.process_time() - t0:.0f} s CPU"
    )
    if not strokes:
        return 0
    print(
        f"  exact strokes that drop: geometry's aim {raw_made / strokes:.0%}, "
        f"corrected {fixed_made / strokes:.0%} ({sims / strokes:.1f} engine shots each)"
    )
    print(f"  under the {LEVELS[-1]}'s noise ({TRIALS} strokes each), by the geometry's chance:")
    for k, rates in by_chance.items():
        if rates:
            print(
                f"    chance {BINS[k]:.1f}-{min(BINS[k + 1], 1.0):.1f}: {len(rates)} {args.kind}s, "
                f"dropped {np.mean(rates):.0%}"
            )
    return 0


if __name__ == "__main__":
    sys.exit(main())
