"""The computer at three-cushion: the pro's points per inning from the opening and from
random positions, the ladder of levels game by game, and how long a plan takes.

    python -m bench.ai --kind three_cushion [--runouts 200] [--games 20] [--race 5]
                       [--only innings,ladder] [--seed 0] [--jobs 1] [--steps pro]

Every stroke is played with the striker's own execution error (`Bot.execute` on the carom
table; the pro's is FastFiz's: sigma aim 0.125 deg, speed 0.075 m/s, tip 0.5 mm).
`--runouts` innings are played from each start: the opening position (the opening stroke
on the red), and random positions of the three balls (a seeded uniform draw on the bed,
the balls at least a ball's width apart and from the cushions); an inning is cut at
`MAX_RUN` points. The ladder plays `--games` games to `--race` points between each level
and the one below, the opening alternating.
"""

from __future__ import annotations

import itertools
import statistics
import time
from collections.abc import Callable, Sequence
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass, replace

import numpy as np

from server.ai import Bot
from server.ai.levels import LEVELS
from server.ai.play import play_turn
from server.engine import BallSet, Table
from server.engine.rack import RED, WHITE, YELLOW
from server.rules import Game

MAX_RUN = 60  # points: an inning this long is cut (a guard on the benchmark's time)
MAX_TURNS = 600  # a game longer than this is decided on points


@dataclass
class Inning:
    points: int
    plans: list[float]


def random_balls(table: Table, rng: np.random.Generator) -> BallSet:
    """The three balls at random on the bed, a ball's width clear of each other and of
    the cushions."""
    r = table.ball_radius
    while True:
        xy = rng.uniform((3 * r, 3 * r), (table.length - 3 * r, table.width - 3 * r), (3, 2))
        if all(np.linalg.norm(xy[a] - xy[b]) > 4 * r for a, b in ((0, 1), (0, 2), (1, 2))):
            return BallSet.place(
                {
                    b: (float(x), float(y))
                    for b, (x, y) in zip((WHITE, YELLOW, RED), xy, strict=True)
                }
            )


def play_inning(args: tuple[str, int, bool]) -> Inning:
    """One inning of `level` from the opening or (`random`) from a random position."""
    level, seed, random = args
    game = Game.new("three_cushion", ["a", "b"], seed=seed)
    if random:
        assert game.carom is not None
        game.carom = replace(game.carom, opening=False)
        game.balls = random_balls(game.table, np.random.default_rng([seed, 7]))
    bot = Bot(level, seed)
    rng = np.random.default_rng(seed)
    plans = []
    while game.turn == 0 and not game.over and game.points[0] < MAX_RUN:
        t0 = time.process_time()
        turn = bot.plan(game, 0)
        plans.append(time.process_time() - t0)
        play_turn(game, 0, turn, bot, rng)
    return Inning(game.points[0], plans)


def play_game(args: tuple[tuple[str, str], int, int]) -> int | None:
    """A game to `race` between `levels` (by seat), seat 0 opening; the winner's seat."""
    levels, seed, race = args
    game = Game.new("three_cushion", list(levels), seed=seed)
    assert game.carom is not None
    game.carom = replace(game.carom, race_to=race)
    bots = [Bot(level, seed * 2 + k) for k, level in enumerate(levels)]
    rng = np.random.default_rng(seed)
    for _ in range(MAX_TURNS):
        if game.over:
            return game.winner
        seat = game.turn
        play_turn(game, seat, bots[seat].plan(game, seat), bots[seat], rng)
    points = game.points
    return None if points[0] == points[1] else int(points[1] > points[0])


def _map(fn: Callable, jobs_args: Sequence, jobs: int) -> list:
    if jobs <= 1:
        return [fn(a) for a in jobs_args]
    with ProcessPoolExecutor(jobs) as pool:
        return list(pool.map(fn, jobs_args))


def innings(count: int, seed: int, jobs: int, level: str = "pro") -> None:
    for random in (False, True):
        t0 = time.perf_counter()
        where = "random positions" if random else "the opening"
        records = _map(play_inning, [(level, seed + k, random) for k in range(count)], jobs)
        points = [r.points for r in records]
        plans = [t for r in records for t in r.plans]
        print(f"{level}, {count} innings from {where}:")
        print(
            f"  points per inning {statistics.mean(points):.2f} "
            f"(+- {1.96 * statistics.stdev(points) / len(points) ** 0.5:.2f}), "
            f"highest run {max(points)}, innings without a point {points.count(0)}, "
            f"cut at {MAX_RUN}: {sum(p >= MAX_RUN for p in points)}"
        )
        print(
            f"  plan time (CPU s): median {statistics.median(plans):.2f}, "
            f"p95 {np.percentile(plans, 95):.2f}, max {max(plans):.2f} over {len(plans)} plans; "
            f"{time.perf_counter() - t0:.0f} s"
        )


def ladder(games: int, seed: int, jobs: int, steps: Sequence[str], race: int) -> None:
    print(f"the ladder (three-cushion games to {race}, each level against the one below):")
    for weak, strong in itertools.pairwise(LEVELS):
        if strong not in steps:
            continue
        args = [
            ((strong, weak) if k % 2 == 0 else (weak, strong), seed + k, race) for k in range(games)
        ]
        winners = _map(play_game, args, jobs)
        won = sum(1 for k, w in enumerate(winners) if w == (0 if k % 2 == 0 else 1))
        print(f"  {strong} beat {weak} in {won} of {games} games ({100 * won / games:.0f} %)")


def main(
    innings_count: int,
    games: int,
    seed: int,
    jobs: int,
    parts: set[str],
    steps: Sequence[str],
    race: int,
) -> int:
    if "innings" in parts or "runouts" in parts:
        innings(innings_count, seed, jobs)
    if "ladder" in parts:
        ladder(games, seed, jobs, steps, race)
    return 0
