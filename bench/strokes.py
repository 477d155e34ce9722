"""How often the pro's pot strokes drop their ball, by speed and tip: the search names a
stroke by a factor of the speed that just reaches the pocket (`geometry.speed_for`), the
same strike speed whatever the tip. A draw slides all the way to its ball against a
friction twenty times the rolling one, so its soft strokes arrive slow or not at all.

    python -m bench.strokes --pots 400 --seed 5

Random one-ball pots that the pro's chance model calls 50 % or more (cue ball and object
ball anywhere on the bed, a random pocket the geometry allows), each stroke aimed for the
throw at the pocket's window as the pro aims (`aim_for_throw`) and played on the same
`TRIALS` draws of the pro's noise as its search plans it.
"""

from __future__ import annotations

import argparse
import functools
import math
import sys
import time

import numpy as np

from server.ai import LEVELS, Bot
from server.ai.aiming import aim_for_throw, aimed, perturb, pocket_window
from server.ai.geometry import GEOMETRIC, ChanceModel, PotOption, pot_options, speed_for
from server.ai.search import LATE_SPEED_FACTORS, SPEED_FACTORS, TIPS
from server.engine import CUE, MAX_SPEED, BallSet, Shot, Table, simulate

TRIALS = 20  # noisy strokes per stroke and pot
LIKELY = 0.5  # the pots measured: those the pro's chance model calls this likely or more
FACTORS = tuple(sorted({*SPEED_FACTORS, *LATE_SPEED_FACTORS}))


def random_pot(
    table: Table,
    rng: np.random.Generator,
    aim: float,
    model: ChanceModel = GEOMETRIC,
    least: float = 0.0,
) -> tuple[BallSet, PotOption]:
    """A cue ball and ball 1 anywhere, at least 1.5 diameters apart, and one of the pots
    of ball 1 that `model` gives a chance of `least` or more: (balls, option)."""
    r = table.ball_radius
    while True:
        obj = (rng.uniform(2 * r, table.length - 2 * r), rng.uniform(2 * r, table.width - 2 * r))
        cue = (rng.uniform(2 * r, table.length - 2 * r), rng.uniform(2 * r, table.width - 2 * r))
        if math.dist(obj, cue) < 3 * r:
            continue
        balls = BallSet.place({CUE: cue, 1: obj})
        options = [o for o in pot_options(table, balls, [1], aim, model=model) if o.chance >= least]
        if options:
            return balls, options[int(rng.integers(len(options)))]


def drops(table: Table, balls: BallSet, shot: Shot, pocket: int) -> bool:
    """Ball 1 in `pocket`, the cue ball still on the table."""
    final = simulate(table, balls, shot).final
    row = final.index(1)
    return bool(
        not final.on_table[row]
        and int(final.pockets[row]) == pocket
        and final.on_table[final.index(CUE)]
    )


def pot_rates(pots: int, seed: int) -> dict[tuple[float, tuple[float, float]], float]:
    """The share of the noisy strokes that drop, by (speed factor, tip), over `pots`
    random pots."""
    table = Table.pool("9ft")
    level = Bot(LEVELS[-1]).level
    rng = np.random.default_rng(seed)
    made = {(f, tip): 0 for f in FACTORS for tip in TIPS}
    for _ in range(pots):
        balls, option = random_pot(table, rng, level.aim, level.chance_model, LIKELY)
        draws = rng.standard_normal((TRIALS, 4))
        window = functools.partial(pocket_window, table, balls, 1, option.pocket)
        for factor in FACTORS:
            speed = min(speed_for(option) * factor, 0.85 * MAX_SPEED)
            for tip in TIPS:
                shot = aimed(option.angle, speed, *tip)
                shot, _ = aim_for_throw(table, balls, shot, 1, option.pocket, window)
                noisy = (perturb(shot, row, level, squirt=True) for row in draws)
                made[factor, tip] += sum(drops(table, balls, s, option.pocket) for s in noisy)
    return {key: count / (pots * TRIALS) for key, count in made.items()}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pots", type=int, default=400)
    parser.add_argument("--seed", type=int, default=5)
    args = parser.parse_args(argv)
    t0 = time.process_time()
    rates = pot_rates(args.pots, args.seed)
    print(
        f"pot strokes of the {LEVELS[-1]} by speed and tip ({args.pots} random pots called "
        f"50 % or more, {TRIALS} noisy strokes each, seed {args.seed}; "
        f"{time.process_time() - t0:.0f} s CPU): share that drop"
    )
    print("  tip (side, height) " + "".join(f"{f:>7.2f}x" for f in FACTORS))
    for tip in TIPS:
        row = "".join(f"{rates[f, tip]:>7.0%} " for f in FACTORS)
        print(f"  {tip!s:<19}{row}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
