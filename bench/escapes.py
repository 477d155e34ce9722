"""How often the top level escapes a blocked ball with and without swerves and masses:
crafted 9-ball tables where a ball sits on the straight line to the 1, further from the
cue ball than a jump reaches (`search.JUMP_REACH`), so only kicks and curves go round it.

    python -m bench.escapes [--layouts 20] [--seed 7200] [--draws 10]
    python -m bench.escapes --kind snooker [--layouts 20] [--seed 7200] [--draws 10]

With `--kind snooker` it measures the escapes from snookers instead (`snooker_escapes`).

Each table is planned by the top level as it is and with its massé turned off; each plan
is played `--draws` times by the level's arm (its noise) and counts as an escape when the
shot is legal (the 1 hit first, then a ball pocketed or at a cushion, no scratch, no ball
off the table). Printed: the share of legal strokes, of those that pocket a ball, and how
many plans raised the cue, for both.
"""

from __future__ import annotations

import argparse
import math
import sys
from dataclasses import replace

import numpy as np

from server.ai import Bot
from server.ai.levels import LEVELS
from server.ai.search import JUMP_REACH
from server.engine import BallSet, MotionState, Table, simulate
from server.rules import Game
from server.rules.shotfacts import shot_facts

from .snooker_escapes import report

TABLE = Table.pool("9ft")
R = TABLE.ball_radius


def blocked_table(rng: np.random.Generator) -> dict[int, tuple[float, float]]:
    """The cue ball, the 1 0.7-1.3 m away, the 2 on the line between them beyond a jump's
    reach (up to touching the 1, up to half a radius off the line), the 9 off to a side."""
    while True:
        cue = (rng.uniform(0.3, TABLE.length - 0.3), rng.uniform(0.3, TABLE.width - 0.3))
        heading, dist = rng.uniform(0, 2 * math.pi), rng.uniform(0.7, 1.3)
        ux, uy = math.cos(heading), math.sin(heading)
        one = (cue[0] + ux * dist, cue[1] + uy * dist)
        along, off = rng.uniform(JUMP_REACH[1] + 0.05, dist - 2 * R - 0.002), rng.uniform(-R, R) / 2
        two = (cue[0] + ux * along - uy * off, cue[1] + uy * along + ux * off)
        nine = (cue[0] - uy * 0.5, cue[1] + ux * 0.5)
        spots = (cue, one, two, nine)
        if all(0.1 < x < TABLE.length - 0.1 and 0.1 < y < TABLE.width - 0.1 for x, y in spots):
            return {0: cue, 1: one, 2: two, 9: nine}


def set_up(placement: dict[int, tuple[float, float]]) -> Game:
    """A 9-ball game after its break with exactly `placement` on the table, seat 0 to shoot."""
    game = Game.new("nine_ball", ["a", "b"], seed=3)
    full = {b: (0.1 + 0.1 * b, 0.1) for b in game.balls.ids.tolist()}
    full.update(placement)
    balls = BallSet.place(full)
    for b in full:
        if b not in placement:
            row = balls.index(b)
            balls.states[row] = MotionState.POCKETED
            balls.pockets[row] = 0
            balls.positions[row] = TABLE.pockets[0].center
    game.balls, game.breaking, game.turn = balls, False, 0
    game.groups = game.ball_in_hand = game.decision = game.pending = None
    return game


def escapes(bot: Bot, tables: list[Game], draws: int, seed: int) -> tuple[float, float, int]:
    """The shares of `bot`'s strokes (each plan played `draws` times) that are legal and
    that pocket a ball legally, and how many of its plans raised the cue."""
    legal = pots = raised = 0
    for i, game in enumerate(tables):
        shot = bot.plan(game, 0).shot
        assert shot is not None
        raised += shot.elevation > 0
        rng = np.random.default_rng(seed + i)
        for _ in range(draws):
            played = bot.execute(shot, rng)
            facts = shot_facts(game.balls, simulate(TABLE, game.balls, played))
            ok = facts.first_contact == 1 and not facts.scratch and not facts.off_table
            ok = ok and (facts.rail_after_contact or bool(facts.pocketed))
            legal += ok
            pots += ok and bool(facts.pocketed)
    strokes = len(tables) * draws
    return legal / strokes, pots / strokes, raised


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--layouts", type=int, default=20)
    parser.add_argument("--seed", type=int, default=7200)
    parser.add_argument("--draws", type=int, default=10)
    parser.add_argument("--kind", choices=("nine_ball", "snooker"), default="nine_ball")
    args = parser.parse_args(argv)
    if args.kind == "snooker":
        report(args.layouts, args.seed, args.draws)
        return 0
    rng = np.random.default_rng(args.seed)
    tables = [set_up(blocked_table(rng)) for _ in range(args.layouts)]
    with_curves = Bot(LEVELS[-1])
    without = Bot(LEVELS[-1])
    without.level = replace(without.level, masse=False)
    for name, bot in (("with swerve/masse", with_curves), ("kicks and jumps only", without)):
        legal, pots, raised = escapes(bot, tables, args.draws, args.seed)
        print(
            f"{name:22s} legal {legal:6.1%}, pocketing {pots:6.1%} of "
            f"{len(tables) * args.draws} strokes; {raised}/{len(tables)} plans raised the cue"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
