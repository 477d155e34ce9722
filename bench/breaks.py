"""How the break strokes do under a level's execution noise: the grid the computer's break
(`server.ai.bot.BREAKS`) was chosen from.

    python -m bench.breaks [--kind eight_ball] [--racks 300] [--seed 1000] [--level pro]
                           [--jobs 2] [--top 12]

Each stroke (the cue ball on the head string, `offset` m beside the long string, hit full
on the head ball at a speed with a tip height) breaks the same racks (`Game.new`'s seeds
from `--seed`) with the same noise draws, and the rules judge each break. Printed, best
first by what the kind's break is chosen on: the share of breaks that keep the table
(a ball down, no foul), that keep it with a pot to follow (the breaker's best pot at least
50 % likely under the level's noise), that foul, and that win the game (9-ball: the 9 on
the break), and how open each leaves the rack (`open_share` of the balls left, the game
ball aside, averaged). Shares with a 95 % Wilson interval; the computer's own stroke is
marked.
"""

from __future__ import annotations

import argparse
import itertools
import sys
import time
from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np

from bench.ai import _map, wilson
from server.ai import LEVELS, Bot
from server.ai.bot import BREAKS, BreakStroke, break_shot, break_spot, head_ball
from server.ai.geometry import best_chance, open_share
from server.engine import simulate
from server.rules import Game
from server.rules.eight_ball import EIGHT
from server.rules.nine_ball import NINE

OFFSETS = (0.0, 0.22, 0.35, 0.5)  # m beside the long string
SPEEDS = (8.0, 9.0, 10.0, 11.0, 12.0)  # m/s
HEIGHTS = (-0.2, 0.0, 0.15)  # tip above centre, a fraction of the radius
FOLLOW_UP = 0.5  # a pot to follow: the breaker's best pot at least this likely
# What each kind's break is chosen on (`BREAKS`): in 9-ball whoever plays after the break
# may push out, so keeping the table counts more than the pot that follows.
CHOSEN_ON = {"eight_ball": "kept with a pot", "nine_ball": "kept"}


@dataclass
class Tally:
    breaks: int = 0
    kept: int = 0
    kept_with_pot: int = 0
    fouls: int = 0
    won: int = 0
    open_sum: float = 0.0  # `open_share` of the balls left after each break, summed

    def add(self, other: Tally) -> None:
        self.breaks += other.breaks
        self.kept += other.kept
        self.kept_with_pot += other.kept_with_pot
        self.fouls += other.fouls
        self.won += other.won
        self.open_sum += other.open_sum

    def measure(self, kind: str) -> int:
        return self.kept_with_pot if CHOSEN_ON[kind] == "kept with a pot" else self.kept


def break_once(kind: str, seed: int, stroke: BreakStroke, level: str) -> Tally:
    """One break of rack `seed` with `stroke` under `level`'s noise, judged by the rules."""
    game = Game.new(kind, ["breaker", "other"], breaker=0, seed=seed)
    bot = Bot(level, seed)
    place = break_spot(game.table, stroke.offset)
    game.place_cue(0, *place)
    balls = game.balls
    shot = break_shot(balls, head_ball(game.rules, game.position(), balls, game.table), stroke)
    shot = bot.execute(shot, np.random.default_rng(seed + 12345))
    game.check_shot(0)
    outcome = game.apply(0, simulate(game.table, balls, shot))
    kept = not game.over and game.turn == 0 and game.decision is None and not outcome.fouls
    pot = False
    if kept:
        pos = game.position()
        targets = game.rules.legal_targets(pos) or pos.object_balls
        level_ = bot.level
        chance = best_chance(game.table, game.balls, targets, level_.aim, model=level_.chance_model)
        pot = chance >= FOLLOW_UP
    won = game.over and game.winner == 0
    return Tally(1, int(kept), int(pot), int(bool(outcome.fouls)), int(won), spread(game))


def spread(game: Game) -> float:
    """How open the break left the rack (`open_share` of the object balls on the table,
    the game ball left out), shown beside what the stroke keeps: a break is chosen on both,
    and a more open rack alone cleared no more runouts (docs/ai.md, "Tried and rejected")."""
    game_ball = EIGHT if game.rules.kind == "eight_ball" else NINE
    balls = [b for b in game.position().object_balls if b != game_ball]
    return open_share(game.table, game.balls, balls)


def _job(args: tuple[str, list[int], BreakStroke, str]) -> Tally:
    kind, seeds, stroke, level = args
    total = Tally()
    for seed in seeds:
        total.add(break_once(kind, seed, stroke, level))
    return total


def strokes() -> list[BreakStroke]:
    grid = [BreakStroke(*p) for p in itertools.product(OFFSETS, SPEEDS, HEIGHTS)]
    return list(dict.fromkeys([*grid, *BREAKS.values()]))


def pct(k: int, n: int) -> str:
    lo, hi = wilson(k, n)
    return f"{100 * k / n:5.1f} % ({100 * lo:.0f}-{100 * hi:.0f})"


def report(kind: str, results: Iterable[tuple[BreakStroke, Tally]], top: int) -> None:
    ranked = sorted(results, key=lambda st: -st[1].measure(kind))
    own = BREAKS[kind]
    head = f"{'offset':>6} {'speed':>5} {'tip':>5}   {'kept':15} {'kept with a pot':15}"
    print(f"  {head} fouls   open")
    for rank, (stroke, t) in enumerate(ranked, 1):
        if rank > top and stroke != own:
            continue
        mark = "  <- the computer's break" if stroke == own else ""
        print(
            f"{rank:3d} {stroke.offset:5.2f} {stroke.speed:5.1f} {stroke.height:5.2f}   "
            f"{pct(t.kept, t.breaks)} {pct(t.kept_with_pot, t.breaks)} "
            f"{100 * t.fouls / t.breaks:4.1f} %  {t.open_sum / t.breaks:.3f}{mark}"
        )


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--kind", default="eight_ball", choices=sorted(BREAKS))
    parser.add_argument("--racks", type=int, default=300, help="racks broken by each stroke")
    parser.add_argument("--seed", type=int, default=1000, help="the first rack's seed")
    parser.add_argument("--level", default=LEVELS[-1], choices=LEVELS)
    parser.add_argument("--jobs", type=int, default=1, help="worker processes")
    parser.add_argument("--top", type=int, default=12, help="strokes printed")
    args = parser.parse_args(argv)
    t0 = time.perf_counter()
    seeds = list(range(args.seed, args.seed + args.racks))
    grid = strokes()
    chunks = [seeds[i::4] for i in range(4)]
    jobs = [(args.kind, chunk, stroke, args.level) for stroke in grid for chunk in chunks]
    tallies = _map(_job, jobs, args.jobs)
    totals = {stroke: Tally() for stroke in grid}
    for (_, _, stroke, _), tally in zip(jobs, tallies, strict=True):
        totals[stroke].add(tally)
    print(
        f"bench.breaks: {args.kind}, {len(grid)} strokes x {args.racks} racks (seeds "
        f"{args.seed}-{args.seed + args.racks - 1}), {args.level}'s noise; ranked by "
        f"{CHOSEN_ON[args.kind]}; {time.perf_counter() - t0:.0f} s"
    )
    report(args.kind, totals.items(), args.top)
    return 0


if __name__ == "__main__":
    sys.exit(main())
