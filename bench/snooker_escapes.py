"""How the computer escapes from snookers at snooker: crafted tables where the one red is
hidden in a straight line behind a colour, planned by each level from the amateur up and
played under its execution error.

    python -m bench.escapes --kind snooker [--layouts 20] [--seed 7200] [--draws 10]

A table: the cue ball anywhere, the red 0.5-2 m away, a colour on the line between them
(its centre up to half a radius off it, at least three radii from either centre), the other
colours on their spots; kept only when no part of the red is in sight (`open_path`, the
WPBSA miss rule's test) and no ball touches another or a cushion. Each plan is played
`--draws` times by the level's arm (`Bot.execute`) and judged by the rules: a stroke is
legal when the red is hit first and there is no foul. Printed per level: the shares of
legal strokes, of fouls and of misses called (WPBSA Section 3, Rule 14), and what the
plans are, read from the exact stroke: off one cushion, off two or more, a jump, a swerve
or masse, or straight ("airborne": the cue ball left the bed, a hop, not necessarily over
a ball).
"""

from __future__ import annotations

import math
import statistics
import time
from collections import Counter
from dataclasses import dataclass, field, replace

import numpy as np

from server.ai import Bot
from server.engine import (
    CUE,
    EventKind,
    FlightKind,
    Settled,
    Shot,
    Table,
    settle,
)
from server.rules import Game
from server.rules.shotfacts import shot_facts
from server.rules.snooker_score import COLOUR_IDS, NAMES
from server.rules.snooker_table import open_path

TABLE = Table.snooker()
R = TABLE.ball_radius
RED = 1
LEVELS = ("amateur", "club", "pro")
SHAPES = ("1 cushion", "2+ cushions", "jump", "swerve/masse", "straight")


def snookered_table(rng: np.random.Generator) -> dict[int, tuple[float, float]]:
    """A placement: the cue ball, the red and a colour between them hiding it (see the
    module's docstring); drawn until one fits on the table."""
    while True:
        cue = (rng.uniform(0.15, TABLE.length - 0.15), rng.uniform(0.15, TABLE.width - 0.15))
        heading, dist = rng.uniform(0, 2 * math.pi), rng.uniform(0.5, 2.0)
        ux, uy = math.cos(heading), math.sin(heading)
        red = (cue[0] + ux * dist, cue[1] + uy * dist)
        along, off = rng.uniform(3 * R, dist - 3 * R), rng.uniform(-R, R) / 2
        hider = (cue[0] + ux * along - uy * off, cue[1] + uy * along + ux * off)
        blocker = int(rng.choice(COLOUR_IDS))
        placement = {b: TABLE.spots[NAMES[b]] for b in COLOUR_IDS}
        placement.update({CUE: cue, RED: red, blocker: hider})
        if _fits(placement) and not open_path(TABLE, set_up(placement).balls, [RED]):
            return placement


def _fits(placement: dict[int, tuple[float, float]]) -> bool:
    """Every ball on the bed, clear of the cushions and of every other ball."""
    xy = np.array(list(placement.values()))
    if not all(TABLE.contains(x, y, 0.01) for x, y in xy):
        return False
    gaps = np.hypot(*(xy[:, None, :] - xy[None, :, :]).transpose(2, 0, 1))
    return bool(np.all(gaps[np.triu_indices(len(xy), 1)] > 2 * R + 1e-3))


def set_up(placement: dict[int, tuple[float, float]]) -> Game:
    """A snooker frame with exactly `placement` on the table, a red on, seat 0 to play."""
    game = Game.new("snooker", ["a", "b"], seed=3)
    balls = game.balls.with_only(placement)
    game.balls, game.ball_in_hand = balls, None
    game.score = replace(game.score, on="red")
    return game


def shape(result: Settled, shot: Shot) -> str:
    """What an exact stroke is (`SHAPES`): a raised cue with no side is a jump (straight
    over the ball in the way), with side a swerve or masse; a level cue by the cushions
    the cue ball met before its first contact."""
    if shot.elevation > 0:
        return SHAPES[2] if shot.tip[0] == 0 else SHAPES[3]
    cushions = 0
    for event in result.events:
        if CUE in event.ids and event.kind == EventKind.BALL:
            break
        cushions += CUE in event.ids and event.kind == EventKind.CUSHION
    return SHAPES[0] if cushions == 1 else SHAPES[1] if cushions >= 2 else SHAPES[4]


@dataclass
class Tally:
    """One level's strokes and plans over the tables."""

    strokes: int = 0
    legal: int = 0
    fouls: int = 0
    misses: int = 0
    exact_legal: int = 0
    shapes: Counter[str] = field(default_factory=Counter)
    airborne: int = 0
    plan_s: list[float] = field(default_factory=list)


def tally(bot: Bot, tables: list[Game], draws: int, seed: int) -> Tally:
    """`bot`'s plan on each table, played exactly (its shape) and `draws` times with the
    level's error (judged by the rules)."""
    out = Tally()
    for i, game in enumerate(tables):
        t0 = time.process_time()
        shot = bot.plan(game, 0).shot
        out.plan_s.append(time.process_time() - t0)
        assert shot is not None
        exact = settle(TABLE, game.balls, shot)
        out.shapes[shape(exact, shot)] += 1
        out.airborne += any(e.kind == FlightKind.LAND for e in exact.events)
        pos, on = game.position(), game.legal_targets()
        facts = shot_facts(game.balls, exact)
        out.exact_legal += facts.first_contact in on and not game.rules.judge(pos, facts).fouls
        rng = np.random.default_rng(seed + i)
        for _ in range(draws):
            played = bot.execute(shot, rng, TABLE)
            facts = shot_facts(game.balls, settle(TABLE, game.balls, played))
            ruling = game.rules.judge(pos, facts)
            out.strokes += 1
            out.legal += facts.first_contact in on and not ruling.fouls
            out.fouls += bool(ruling.fouls)
            out.misses += ruling.miss
    return out


def bots() -> list[tuple[str, Bot]]:
    """The levels from the amateur up, and the pro with its cue kept level (no jump,
    swerve or masse): its escapes by kicks alone."""
    out = [(level, Bot(level)) for level in LEVELS]
    level_cue = Bot(LEVELS[-1])
    level_cue.level = replace(level_cue.level, jumps=False, masse=False)
    return [*out, ("pro, cue level", level_cue)]


def report(layouts: int, seed: int, draws: int) -> None:
    """Print each level's figures on `layouts` tables drawn from `seed`."""
    rng = np.random.default_rng(seed)
    tables = [set_up(snookered_table(rng)) for _ in range(layouts)]
    print(f"{layouts} snookers on the red, each plan played {draws} times:")
    for name, bot in bots():
        t = tally(bot, tables, draws, seed)
        plans = ", ".join(f"{shape} {t.shapes[shape]}" for shape in SHAPES)
        print(
            f"{name:14s} legal {t.legal / t.strokes:6.1%}, fouls {t.fouls / t.strokes:6.1%}, "
            f"misses called {t.misses / t.strokes:5.1%} of {t.strokes} strokes; "
            f"plans: {plans} ({t.airborne} airborne), {t.exact_legal} legal played exactly; "
            f"plan CPU median {statistics.median(t.plan_s):.2f} s, max {max(t.plan_s):.2f} s"
        )
