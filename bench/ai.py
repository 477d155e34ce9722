"""Computer-opponent benchmark: runouts, the strongest level against a greedy baseline, the
ladder of levels, plan times and per-game counts.

    python -m bench.ai [--games 200] [--runouts 200] [--only runouts,greedy,ladder,loop]
                       [--kind eight_ball] [--seed 0] [--jobs 1]
                       [--rooms 2] [--workers 1] [--seconds 10] [--configs 1200] [--fit]
                       [--save outcomes.json] [--paired earlier.json]
                       [--noise aim,speed,tip] [--table 9ft] [--steps pro]

`calibrate`: the pot chance the search plans with against the engine's measured rates
under the top level's noise (what `geometry.FASTFIZ` was fitted to); `--fit` refits it.

`loop`: how late the server's event loop runs (what every room's frames wait) while
computer seats plan in threads or in worker processes, as `server.rooms.computer` does.

Every shot is played with the executing player's noise (`Bot.execute`); the greedy
baseline plays with the top level's noise (FastFiz: sigma aim 0.125 deg, speed 0.075 m/s,
tip 0.5 mm). Breaks alternate. Shares are printed with a 95 % Wilson interval.

With the counts per game the top level's pots are counted by the chance its plan gave
them (`Turn.chance`, the share of its noisy trials that dropped), and the runouts say how
each rack not cleared ended (a missed pot planned at 90 % or more, a harder one, a safety,
a foul, the 8 lost).

`--noise` plays the runouts' strokes with only some parts of the execution error (the
plans still assume the level's own): `none` for exact strokes, `aim` or `aim,speed` to
see what each part costs, `aim,speed,tip,squirt` with the tip's error turning the cue
ball's line as well (an arm that does not allow for the squirt of the tip it strikes),
`ball-speed` with the speed's sigma on the ball's speed, not the cue's (FastFiz's is the
cue's; docs/ai.md, "Levels"). It says what the racks are lost to.

`--table` plays every rack and game on an 8ft or 7ft table instead of the rooms' 9ft, or
on `fastfiz`, the tournaments' own table in our engine (2.236 x 1.116 m, and pockets
without jaws: a ball drops as it crosses the pocket's line; `bench/fastfiz.py`).

`--kind snooker` plays snooker frames (`bench/snooker.py`): the pro's self-play (the
highest break per frame, centuries, plan times; `--only frames`) and the ladder, `--games`
frames each.

`--kind three_cushion` plays three-cushion (`bench/carom.py`): the pro's points per inning
over `--runouts` innings from the opening and from random positions, plan times, and the
ladder (`--games` games to `--race` points; `--only innings,ladder`).

`--kind nine_ball` plays the runouts, the greedy games and the ladder at 9-ball (the
goals are 8-ball's): a runout starts with ball in hand after the pro's 9-ball break, the 9
on the table, no push out; the greedy baseline shoots the lowest ball.

`--save` writes each rack's and game's outcome by seed; `--paired` compares this run with
such a file seed by seed. A seed gives the same rack and the same noise draws, so two
versions of the search differ only where their play differs: the sign test on the seeds
only one of them won detects a change of a few points that two 200-rack shares (each
about +-6 points) cannot.
"""

from __future__ import annotations

import argparse
import asyncio
import functools
import itertools
import json
import math
import multiprocessing
import statistics
import sys
import time
from collections.abc import Callable
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass, field

import numpy as np
from numba import njit

from bench.fastfiz import fastfiz_table
from server.ai import LEVELS, Bot, Turn, play_turn
from server.ai.aiming import clamp_shot, perturb
from server.ai.bot import NormalSource, level_at
from server.ai.geometry import (
    ChanceModel,
    clean_window,
    drop_chance,
    ghost_error,
    object_sigma,
    pot_options,
    speed_for,
)
from server.ai.levels import BY_NAME, Level
from server.ai.play import warm_up
from server.codec import to_data
from server.engine import CUE, TICK_HZ, Shot, Table
from server.engine.table import TABLE_SIZES
from server.rooms.computer import plan_turn
from server.rules import ANYWHERE, Game, Outcome
from server.rules.placement import can_place

MAX_TURNS = 200  # a game longer than this is stopped and counted as a draw
GAME_BALL = {"eight_ball": 8, "nine_ball": 9}  # the ball that wins each kind's rack
TICK = 1.0 / TICK_HZ  # s: the stream's frame clock, the loop-lateness probe's period
TABLES = (*sorted(TABLE_SIZES), "fastfiz")  # `--table`: a WPA size, or FastFiz's table


def table_named(name: str) -> Table:
    """The table `--table` names: a WPA pool table by size, or FastFiz's (`bench.fastfiz`)."""
    return fastfiz_table() if name == "fastfiz" else Table.pool(name)


# --- the greedy baseline --------------------------------------------------------------
class Greedy:
    """Ghost ball at the pocket with the smallest cut and clear paths, a fixed-ish speed, no
    spin, no safeties (no pot: straight at the nearest legal ball). Executes with the top
    level's noise."""

    name = "greedy"

    def __init__(self) -> None:
        self._arm = Bot(LEVELS[-1])
        self.last_sims = 0

    def execute(self, shot: Shot, rng: NormalSource, table: Table | None = None) -> Shot:
        return self._arm.execute(shot, rng, table)

    def plan(self, game: Game, seat: int) -> Turn:  # noqa: ARG002 (`Bot.plan`'s signature)
        if game.decision is not None:
            return Turn(decision=game.decision.options[0])
        table, balls = game.table, game.balls
        pos = game.position()
        targets = game.legal_targets() or pos.object_balls
        place = None
        if game.ball_in_hand is not None:
            place = self._place(game, targets)
            balls = balls.with_ball(CUE, place)
        if game.breaking:
            head = min(targets, key=lambda t: math.dist(balls.position_of(t), table.foot_spot))
            cx, cy = balls.position_of(CUE)
            hx, hy = balls.position_of(head)
            return Turn(place=place, shot=Shot(math.atan2(hy - cy, hx - cx), 10.0), kind="break")
        options = pot_options(table, balls, targets, math.radians(0.125))
        if options:
            best = min(options, key=lambda o: o.cut)
            speed = min(max(2.0, 1.5 * speed_for(best)), 6.0)
            call = best.pocket if game.requires_call else None
            shot = clamp_shot(best.angle, speed, 0.0, 0.0)
            return Turn(place=place, call=call, shot=shot, kind="pot", target=best.target)
        cx, cy = balls.position_of(CUE)
        on = set(balls.on_table_ids())
        near = min(
            (t for t in targets if t in on), key=lambda t: math.dist(balls.position_of(t), (cx, cy))
        )
        nx, ny = balls.position_of(near)
        call = 0 if game.requires_call else None
        shot = Shot(math.atan2(ny - cy, nx - cx), 2.0)
        return Turn(place=place, call=call, shot=shot, kind="safety", target=near)

    def _place(self, game: Game, targets: list[int]) -> tuple[float, float]:
        table, balls = game.table, game.balls
        r = table.ball_radius
        spots = []
        on = set(balls.on_table_ids())
        for t in targets:
            if t not in on:
                continue
            ox, oy = balls.position_of(t)
            for p in table.pockets:
                (ax, ay), (bx, by) = p.jaws
                ux, uy = (ax + bx) / 2 - ox, (ay + by) / 2 - oy
                n = math.hypot(ux, uy) or 1.0
                spots.append((ox - ux / n * (2 * r + 0.3), oy - uy / n * (2 * r + 0.3)))
        spots += [
            (float(x), float(y))
            for x in np.linspace(2 * r, table.length - 2 * r, 12)
            for y in np.linspace(2 * r, table.width - 2 * r, 6)
        ]
        for x, y in spots:
            if can_place(table, balls, game.ball_in_hand, x, y):
                return (x, y)
        raise RuntimeError("no place for the cue ball")


Player = Bot | Greedy


# --- the execution error, in parts --------------------------------------------------------
NOISE_PARTS = ("aim", "speed", "tip", "squirt", "ball-speed")
FULL_NOISE = ("aim", "speed", "tip")


@dataclass(frozen=True)
class Arm:
    """A level's execution error with only some of its parts (`--noise`): "aim" (the
    line), "speed", "tip" (the spin the tip's error gives) and "squirt" (with "tip": the
    tip's error also turns the cue ball's line by its squirt, as for an arm that does not
    allow for it, `perturb(squirt=True)`) and "ball-speed" (with "speed": the speed's
    sigma on the ball's speed, not the cue's, `perturb(cue_speed=False)`). Four normals
    are drawn whatever the parts, so a seed's shots get the same draws in every variant
    and runs compare seed by seed."""

    level: Level
    parts: tuple[str, ...] = FULL_NOISE

    def execute(self, shot: Shot, rng: NormalSource, table: Table | None = None) -> Shot:
        draws = np.array([float(rng.normal(0.0, 1.0)) for _ in range(4)])
        parts = self.parts
        keep = np.array(["aim" in parts, "speed" in parts, "tip" in parts, "tip" in parts])
        return perturb(
            shot,
            draws * keep,
            level_at(self.level, table),
            squirt="squirt" in parts,
            cue_speed="ball-speed" not in parts,
        )


# The runouts' break is played with the arm the layouts were first measured with (the
# tip's error squirting the cue ball, the speed's sigma on the ball's speed): a break is
# chaotic, and so a seed keeps the layout every figure in docs/ai.md was measured on, and
# runs of any version compare seed by seed.
BREAK_NOISE = (*FULL_NOISE, "squirt", "ball-speed")


def known_names(text: str, known: tuple[str, ...], what: str) -> tuple[str, ...]:
    """An option's comma list of names, each one of `known` (empty items skipped)."""
    names = tuple(name for name in text.split(",") if name)
    unknown = [name for name in names if name not in known]
    if unknown:
        raise argparse.ArgumentTypeError(f"unknown {what} {unknown[0]!r}: {known}")
    return names


def noise_parts(text: str) -> tuple[str, ...]:
    """`--noise`'s comma list: parts of `NOISE_PARTS`, or "none" for exact strokes."""
    parts = known_names(text, (*NOISE_PARTS, "none"), "noise part")
    return tuple(part for part in parts if part != "none")


# --- statistics -----------------------------------------------------------------------
def wilson(successes: int, n: int, z: float = 1.96) -> tuple[float, float]:
    if n == 0:
        return (0.0, 1.0)
    p = successes / n
    denom = 1 + z * z / n
    centre = (p + z * z / (2 * n)) / denom
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / denom
    return (max(0.0, centre - half), min(1.0, centre + half))


def share(successes: int, n: int) -> str:
    lo, hi = wilson(successes, n)
    pct = 100 * successes / n if n else 0.0
    return f"{successes}/{n} = {pct:.1f} % (95 % CI {100 * lo:.1f}-{100 * hi:.1f} %)"


def sign_test(only_a: int, only_b: int) -> float:
    """Two-sided exact p of a paired comparison (McNemar's test): the chance, were both
    versions equally strong, of a split of the discordant seeds at least this uneven."""
    n, k = only_a + only_b, min(only_a, only_b)
    if n == 0:
        return 1.0
    tail = sum(math.comb(n, i) for i in range(k + 1)) / 2**n
    return min(1.0, 2 * tail)


Outcomes = dict[str, dict[str, bool]]  # comparison -> seed (as text) -> won


def report_paired(now: Outcomes, before: Outcomes, label: str) -> None:
    """Each comparison of this run against the same one in `before`, on their common seeds."""
    for name, results in now.items():
        earlier = before.get(name, {})
        common = [s for s in results if s in earlier]
        if not common:
            continue
        here = sum(results[s] and not earlier[s] for s in common)
        there = sum(earlier[s] and not results[s] for s in common)
        won_now = sum(results[s] for s in common)
        won_then = sum(earlier[s] for s in common)
        print(
            f"paired with {label}, {name}: {won_now} against {won_then} of {len(common)};"
            f" won only now {here}, only then {there}; sign test p = {sign_test(here, there):.3f}"
        )


@dataclass
class Counts:
    """Per player (by name): shots, pots (legal, a ball of theirs dropped and they kept
    the table or won), fouls, safeties (shots planned as safeties or kicks), breaks and the
    breaks after which they kept the table, plan times."""

    games: int = 0
    shots: dict[str, int] = field(default_factory=dict)
    pots: dict[str, int] = field(default_factory=dict)
    pot_tries: dict[str, int] = field(default_factory=dict)
    fouls: dict[str, int] = field(default_factory=dict)
    safeties: dict[str, int] = field(default_factory=dict)
    breaks: dict[str, int] = field(default_factory=dict)
    breaks_kept: dict[str, int] = field(default_factory=dict)
    times: dict[str, list[float]] = field(default_factory=dict)  # wall clock per plan
    cpu: dict[str, list[float]] = field(default_factory=dict)  # CPU time per plan (one core)
    # Per pot tried: the chance its plan gave it (`Turn.chance`) and whether it dropped.
    chances: dict[str, list[tuple[float, bool]]] = field(default_factory=dict)
    ends: dict[str, int] = field(default_factory=dict)  # runouts: how each lost rack ended
    # Runouts: the balls the lost rack's last shot had left to pot, the 8 counted.
    left: dict[str, int] = field(default_factory=dict)

    def add(self, other: Counts) -> None:
        self.games += other.games
        for name in (
            "shots",
            "pots",
            "pot_tries",
            "fouls",
            "safeties",
            "breaks",
            "breaks_kept",
            "ends",
            "left",
        ):
            mine, theirs = getattr(self, name), getattr(other, name)
            for k, v in theirs.items():
                mine[k] = mine.get(k, 0) + v
        for name in ("times", "cpu", "chances"):
            mine, theirs = getattr(self, name), getattr(other, name)
            for k, v in theirs.items():
                mine.setdefault(k, []).extend(v)

    def bump(self, table: str, who: str, by: int = 1) -> None:
        d = getattr(self, table)
        d[who] = d.get(who, 0) + by

    def tally(self, who: str, turn: Turn, outcome: Outcome) -> None:
        """One shot of `who`, as the rules judged it (`outcome`)."""
        made = made_pot(outcome)
        self.bump("shots", who)
        if turn.kind in ("safety", "kick"):
            self.bump("safeties", who)
        if turn.kind == "break":
            self.bump("breaks", who)
            self.bump("breaks_kept", who, int(made))
        if turn.kind == "pot":
            self.bump("pot_tries", who)
            self.bump("pots", who, int(made))
            if turn.chance is not None:
                self.chances.setdefault(who, []).append((turn.chance, made))
        if outcome.fouls:
            self.bump("fouls", who)


# The bands of `Turn.chance` the pots made are counted in (the last: every trial dropped).
CHANCE_BANDS = ((0.0, 0.5), (0.5, 0.8), (0.8, 0.9), (0.9, 1.0), (1.0, 1.0))
SURE = 0.9  # a pot planned at least this likely that misses ends a rack as a "sure" miss


def end_of_rack(turn: Turn, outcome: Outcome, lost: bool, game_ball: int = 8) -> str:
    """How a runout ended that did not clear the table."""
    if lost:
        return f"lost on the {game_ball}"
    if outcome.fouls:
        return "fouled"
    if turn.kind == "pot":
        sure = turn.chance is not None and turn.chance >= SURE
        return "missed a sure pot" if sure else "missed a harder pot"
    return "played safe"


def make_player(name: str, seed: int) -> Player:
    return Greedy() if name == "greedy" else Bot(name, seed)


def play_game(
    kind: str, names: tuple[str, str], breaker: int, seed: int, table: str = "9ft"
) -> tuple[int | None, Counts]:
    """One game on a `table` (one of `TABLES`: "7ft", "8ft", "9ft" or "fastfiz"); returns
    the winning seat (None when stopped) and the counts."""
    game = Game.new(kind, list(names), breaker=breaker, seed=seed, table=table_named(table))
    players = [make_player(names[0], seed * 2 + 1), make_player(names[1], seed * 2 + 2)]
    rng = np.random.default_rng(seed + 12345)
    counts = Counts(games=1)
    for _ in range(MAX_TURNS):
        if game.over:
            break
        seat = game.decision.seat if game.decision else game.turn
        player = players[seat]
        t0, c0 = time.perf_counter(), time.process_time()
        turn = player.plan(game, seat)
        who = names[seat]
        counts.times.setdefault(who, []).append(time.perf_counter() - t0)
        counts.cpu.setdefault(who, []).append(time.process_time() - c0)
        outcome, _ = play_turn(game, seat, turn, player, rng)
        if outcome is None:
            continue
        counts.tally(who, turn, outcome)
    return (game.winner if game.over else None), counts


def _game_job(args: tuple[str, tuple[str, str], int, int, str]) -> tuple[int | None, Counts]:
    return play_game(*args)


def runout_position(
    seed: int, rng: np.random.Generator, table: str = "9ft", kind: str = "eight_ball"
) -> Game:
    """The runouts' start: the top level breaks rack `seed` of `kind` on a `table` (with
    `BREAK_NOISE`, so that a seed's layout is the same whatever the parts and the version),
    then seat 1 has ball in hand anywhere: on an open table in 8-ball, the 8 on it; in
    9-ball the 9 on it and no push out."""
    top = LEVELS[-1]
    game = Game.new(kind, ["breaker", top], breaker=0, seed=seed, table=table_named(table))
    breaker = Bot(top, seed + 777)
    turn = breaker.plan(game, 0)
    play_turn(game, 0, turn, Arm(BY_NAME[top], BREAK_NOISE), rng)
    # The position the benchmark asks for: seat 1, ball in hand anywhere, open table.
    game.decision = game.pending = game.after_decision_bih = None
    game.over, game.winner, game.reason = False, None, None
    game_ball = GAME_BALL[kind]
    if game_ball not in game.balls.on_table_ids():
        from server.rules.spotting import respot

        game.balls = respot(game.table, game.balls, (game_ball,))
    game.breaking, game.groups, game.turn = False, None, 1
    game.ball_in_hand, game.push_out_available = ANYWHERE, False
    return game


def runout(
    seed: int,
    noise: tuple[str, ...] = FULL_NOISE,
    table: str = "9ft",
    kept: Callable[[Game], None] | None = None,
    kind: str = "eight_ball",
) -> tuple[bool, Counts]:
    """After a break (the top level's, with noise), the top level gets ball in hand
    (`runout_position`, an 8-ball or 9-ball rack by `kind`): does it clear the table and
    win without leaving it? Its strokes are played with the parts `noise` of its execution
    error. `kept` is shown the game after each stroke that keeps the table
    (`bench.leaves`)."""
    top = LEVELS[-1]
    arm = Arm(BY_NAME[top], noise)
    rng = np.random.default_rng(seed + 999)
    game = runout_position(seed, rng, table, kind)
    bot = Bot(top, seed)
    counts = Counts(games=1)
    for _ in range(40):
        left = balls_to_pot(game, 1)
        t0, c0 = time.perf_counter(), time.process_time()
        plan = bot.plan(game, 1)
        counts.times.setdefault(top, []).append(time.perf_counter() - t0)
        counts.cpu.setdefault(top, []).append(time.process_time() - c0)
        outcome, _ = play_turn(game, 1, plan, arm, rng)
        assert outcome is not None
        counts.tally(top, plan, outcome)
        if game.over and game.winner == 1:
            return True, counts
        if game.over or game.turn != 1 or game.decision is not None:
            counts.bump("ends", end_of_rack(plan, outcome, game.over, GAME_BALL[kind]))
            counts.bump("left", str(left))
            return False, counts
        if kept is not None:
            kept(game)
    counts.bump("ends", "out of turns")
    counts.bump("left", str(left))  # what the last shot had left, as for the others
    return False, counts


def balls_to_pot(game: Game, seat: int) -> int:
    """The balls `seat` has left to pot, the game ball counted: in 8-ball its group's and
    the 8 once the groups are chosen, every object ball on an open table; in 9-ball every
    object ball."""
    groups = game.balls_left()
    if groups is None:
        return sum(1 for b in game.balls.on_table_ids() if b != CUE)
    return len(groups[seat]) + (1 if game.kind == "eight_ball" else 0)


def made_pot(outcome: Outcome) -> bool:
    """A ball of the shooter's dropped and it kept the table, or it won."""
    return bool(outcome.continues and not outcome.fouls and outcome.pocketed) or (
        outcome.winner == outcome.shooter
    )


# --- the event loop while the computer thinks --------------------------------------------
def sample_positions(count: int, seed: int) -> list[tuple[dict, int]]:
    """Positions of real games (the top level against the greedy baseline, the top level to
    play), as game data: what a room hands its planner."""
    out: list[tuple[dict, int]] = []
    s = seed
    while len(out) < count:
        game = Game.new("eight_ball", [LEVELS[-1], "greedy"], breaker=0, seed=s)
        players: list[Player] = [Bot(LEVELS[-1], s), Greedy()]
        rng = np.random.default_rng(s)
        for _ in range(MAX_TURNS):
            if game.over or len(out) >= count:
                break
            seat = game.decision.seat if game.decision else game.turn
            if seat == 0 and game.decision is None:
                out.append((to_data(game), seat))
            play_turn(game, seat, players[seat].plan(game, seat), players[seat], rng)
        s += 1
    return out


async def loop_lateness(
    positions: list[tuple[dict, int]], rooms: int, workers: int, seconds: float
) -> tuple[list[float], int]:
    """`rooms` computer seats plan one position after another, as rooms do (`workers` planner
    processes; 0: threads), while a 120 Hz timer on the event loop measures how late it
    wakes: what every other room's frames wait. Returns (lateness per tick, plans made)."""
    loop = asyncio.get_running_loop()
    if rooms:  # start the planner processes and load the engine first
        await asyncio.gather(*(plan_turn(LEVELS[0], 0, *positions[0], workers) for _ in range(2)))
    stop = False
    plans = 0

    async def think(k: int) -> None:
        nonlocal plans
        while not stop:
            data, seat = positions[k % len(positions)]
            await plan_turn(LEVELS[-1], 0, data, seat, workers)
            plans += 1
            k += rooms

    tasks = [asyncio.create_task(think(k)) for k in range(rooms)]
    lateness: list[float] = []
    start = loop.time()
    due = start + TICK
    while due - start < seconds:
        await asyncio.sleep(max(0.0, due - loop.time()))
        lateness.append(loop.time() - due)
        due += TICK
    stop = True
    await asyncio.gather(*tasks)
    return lateness, plans


def loop_report(rooms: int, workers: int, seconds: float, seed: int) -> None:
    positions = sample_positions(24, seed)
    print(
        f"the event loop while {rooms} computer seats plan ({LEVELS[-1]}, back to back, "
        f"{seconds:g} s each; a 120 Hz timer's lateness):"
    )
    for label, n, w in (
        ("nobody planning", 0, 0),
        ("threads", rooms, 0),
        (f"{workers} worker process(es)", rooms, workers),
    ):
        late, plans = asyncio.run(loop_lateness(positions, n, w, seconds))
        ms = sorted(1e3 * x for x in late)
        print(
            f"  {label:>24}: {plans} plans; lateness p50 {ms[len(ms) // 2]:.1f} ms, "
            f"p99 {ms[int(len(ms) * 0.99)]:.1f} ms, max {ms[-1]:.1f} ms"
        )


# --- the pot-chance model against the engine ----------------------------------------------
CALIBRATE_TRIALS = 30  # noisy strokes per configuration


def pot_rates(configs: int, seed: int) -> np.ndarray:
    """Random one-ball pots (cue ball, object ball and pocket anywhere the geometry allows),
    each played `CALIBRATE_TRIALS` times with the top level's noise as its search plans it
    (the tip's error squirting the line too, `Search.noisy`; centre ball, 1.8 or 2.4
    times the speed that just reaches, aimed for the throw as the computer aims, at the
    middle of the pocket's window when the level aims so): rows of (d1, d2, cut, side
    pocket, cos of the approach to the mouth, measured rate)."""
    from bench.strokes import drops, random_pot
    from server.ai.aiming import aim_for_throw, aimed, perturb, pocket_window
    from server.ai.geometry import pockets_of
    from server.engine import Table

    table = Table.pool("9ft")
    level = Bot(LEVELS[-1]).level
    pk = pockets_of(table)
    rng = np.random.default_rng(seed)
    rows: list[tuple[float, ...]] = []
    while len(rows) < configs:
        balls, o = random_pot(table, rng, level.aim)
        ox, oy = balls.position_of(1)
        factor = (1.8, 2.4)[int(rng.integers(2))]
        shot = aimed(o.angle, min(speed_for(o) * factor, 0.85 * 12.0), 0.0, 0.0)
        window = None
        if level.windows:
            window = functools.partial(pocket_window, table, balls, 1, o.pocket)
        shot, _ = aim_for_throw(table, balls, shot, 1, o.pocket, window)
        made = 0
        for _ in range(CALIBRATE_TRIALS):
            draws = rng.standard_normal(4)
            made += drops(table, balls, perturb(shot, draws, level, squirt=True), o.pocket)
        ux, uy = pk.aims[o.pocket][0] - ox, pk.aims[o.pocket][1] - oy
        cos_in = (ux * pk.outward[o.pocket][0] + uy * pk.outward[o.pocket][1]) / math.hypot(ux, uy)
        rows.append((o.d1, o.d2, o.cut, pk.side[o.pocket], cos_in, made / CALIBRATE_TRIALS))
    return np.array(rows)


@njit(cache=True)
def _model_kernel(data: np.ndarray, params: np.ndarray, aim: float, r: float) -> np.ndarray:
    """The chance a model (aim scale, floor, cut, jaw, side) gives each row of `pot_rates`,
    with the pot kernel's own helpers (`clean_window`, `ghost_error`, `object_sigma`,
    `drop_chance`); compiled, so a grid of models is quick."""
    aim_scale, floor, cut_sigma, jaw, side_cost = params
    out = np.empty(len(data))
    for i in range(len(data)):
        d1, d2, cut, side, cos_in = data[i, 0], data[i, 1], data[i, 2], data[i, 3], data[i, 4]
        mouth = 0.127 if side > 0 else 0.114
        window = clean_window(mouth, cos_in, r, jaw) - side_cost * side
        s_aim = ghost_error(d1, aim, math.cos(cut), r, aim_scale)
        sigma = object_sigma(s_aim, math.sin(cut), floor, cut_sigma, 0.0)
        out[i] = min(max(drop_chance(max(window, 1e-4), d2, sigma), 1e-4), 1 - 1e-4)
    return out


def model_rates(data: np.ndarray, model: ChanceModel, aim: float, r: float) -> np.ndarray:
    """The chance `model` gives each row of `pot_rates`."""
    params = np.array([model.aim_scale, model.floor, model.cut, model.jaw, model.side])
    return _model_kernel(np.ascontiguousarray(data), params, aim, r)


# The grid `calibrate` refits the model on (`geometry.FASTFIZ` is its best point on 3,000
# pots, seed 11): aim scale, floor (rad), cut term (rad), jaw (m), side-pocket cost (m).
FIT_GRID = (
    (1.0, 1.2, 1.4, 1.6, 1.8, 2.0, 2.4, 2.8),
    (0.0, 0.005, 0.01, 0.015, 0.02, 0.025),
    (0.0, 0.02, 0.04, 0.06),
    (0.0, 0.008, 0.016, 0.024, 0.032, 0.04, 0.048),
    (0.0, 0.01, 0.02),
)
EASY = 0.7  # the pots `calibrate` ranks among: those a model calls at least this likely


def log_loss(chance: np.ndarray, rate: np.ndarray) -> float:
    """Mean negative log-likelihood per pot of the measured rates (`CALIBRATE_TRIALS`
    strokes each) under `chance`."""
    n = CALIBRATE_TRIALS
    return float(-(n * (rate * np.log(chance) + (1 - rate) * np.log(1 - chance))).mean())


def rank_correlation(a: np.ndarray, b: np.ndarray) -> float:
    """Spearman's rank correlation (ties broken by order): how well `a` orders `b`."""
    ra, rb = np.argsort(np.argsort(a)), np.argsort(np.argsort(b))
    return float(np.corrcoef(ra, rb)[0, 1])


def refit(data: np.ndarray, aim: float, r: float) -> tuple[float, ChanceModel]:
    """The model of `FIT_GRID` with the least log-loss on `data`: (log-loss, model)."""
    rows, rate = np.ascontiguousarray(data), data[:, 5]
    best: tuple[float, ChanceModel] | None = None
    for params in itertools.product(*FIT_GRID):
        chance = _model_kernel(rows, np.array(params), aim, r)
        loss = log_loss(chance, rate)
        if best is None or loss < best[0]:
            best = (loss, ChanceModel(*params))
    assert best is not None
    return best


def calibrate(configs: int, seed: int, fit: bool = False) -> None:
    """Measure pot rates under the top level's noise and compare the plain geometric
    chance (at the aim sigma position play plans with) with the fitted model
    (`geometry.FASTFIZ`): log-loss, rates by distance, and how well each orders the
    likely pots (what position play compares); `fit` also refits the model on the grid."""
    from server.ai.geometry import FASTFIZ, GEOMETRIC, MIN_AIM_SIGMA

    t0 = time.perf_counter()
    data = pot_rates(configs, seed)
    aim, r = Bot(LEVELS[-1]).level.aim, 0.028575
    plain = model_rates(data, GEOMETRIC, max(aim, MIN_AIM_SIGMA), r)
    fitted = model_rates(data, FASTFIZ, aim, r)
    rate = data[:, 5]
    print(
        f"pot chance vs the engine ({configs} pots x {CALIBRATE_TRIALS} noisy strokes, "
        f"{time.perf_counter() - t0:.0f} s): log-loss per pot plain "
        f"{log_loss(plain, rate):.2f}, fitted {log_loss(fitted, rate):.2f}"
    )
    easy = (plain >= EASY) | (fitted >= EASY)
    print(
        f"  rank correlation with the measured rates: all pots plain "
        f"{rank_correlation(plain, rate):.3f}, fitted {rank_correlation(fitted, rate):.3f}; "
        f"the {int(easy.sum())} pots either calls {EASY:.0%} or more plain "
        f"{rank_correlation(plain[easy], rate[easy]):.3f}, fitted "
        f"{rank_correlation(fitted[easy], rate[easy]):.3f}"
    )
    for name, col, edges in (
        ("cue->object m", 0, (0, 0.3, 0.6, 1.0, 1.5, 3.0)),
        ("object->pocket m", 1, (0, 0.3, 0.6, 1.0, 1.5, 3.0)),
        ("cut deg", 2, (0, 15, 30, 45, 60, 80)),
    ):
        x = np.degrees(data[:, col]) if col == 2 else data[:, col]
        for lo, hi in itertools.pairwise(edges):
            m = (x >= lo) & (x < hi)
            if m.any():
                print(
                    f"  {name} {lo}-{hi}: {int(m.sum())} pots, measured {rate[m].mean():.2f}, "
                    f"plain {plain[m].mean():.2f}, fitted {fitted[m].mean():.2f}"
                )
    short = data[:, 0] < 0.3
    for lo, hi in ((0.0, 0.8), (0.8, 1.3), (1.3, 3.5)):
        m = short & (data[:, 1] >= lo) & (data[:, 1] < hi)
        if m.any():
            print(
                f"  cue->object under 0.3 m, object->pocket {lo}-{hi} m: {int(m.sum())} pots, "
                f"measured {rate[m].mean():.2f}, plain {plain[m].mean():.2f}, "
                f"fitted {fitted[m].mean():.2f}"
            )
    if fit:
        t1 = time.perf_counter()
        loss, best = refit(data, aim, r)
        print(
            f"  refit on the grid ({time.perf_counter() - t1:.0f} s): log-loss {loss:.2f} with "
            f"aim_scale={best.aim_scale}, floor={best.floor}, cut={best.cut}, jaw={best.jaw}, "
            f"side={best.side}"
        )


def _map(fn: Callable, jobs_args: list, jobs: int) -> list:
    """`fn` over `jobs_args` in `jobs` processes. Each loads the compiled kernels and plans
    once first (`warm_up`, as a room's planner does): otherwise the first plan of a worker
    counted numba's compiling (14-18 s of CPU on a cold cache) in the plan time's maximum.
    Spawned, like the room's planners, so a worker inherits nothing compiled."""
    if jobs <= 1:
        warm_up()
        return [fn(a) for a in jobs_args]
    spawn = multiprocessing.get_context("spawn")
    with ProcessPoolExecutor(jobs, mp_context=spawn, initializer=warm_up) as pool:
        return list(pool.map(fn, jobs_args, chunksize=1))


def report_chances(counts: Counts, who: str) -> None:
    """The chance `who`'s plans gave their pots against the share that dropped, by band:
    a search that picks the best of many noisy estimates overrates what it picks."""
    tried = counts.chances.get(who, [])
    if not tried:
        return
    parts = []
    for lo, hi in CHANCE_BANDS:
        band = [made for chance, made in tried if lo <= chance < hi or chance == hi == lo]
        if band:
            name = "100" if lo == hi else f"{100 * lo:.0f}-{100 * hi:.0f}"
            parts.append(f"{name} %: {sum(band)}/{len(band)}")
    print(f"    {who:>9}: pots made by the chance planned, {'; '.join(parts)}")


def report_counts(counts: Counts, names: list[str]) -> None:
    for who in names:
        shots = counts.shots.get(who, 0)
        g = max(counts.games, 1)
        tries = counts.pot_tries.get(who, 0)
        pots = counts.pots.get(who, 0)
        times = counts.times.get(who, []) or [0.0]
        cpu = counts.cpu.get(who, []) or [0.0]
        rate = f"{100 * pots / tries:.0f} %" if tries else "-"
        breaks = counts.breaks.get(who, 0)
        kept = f", kept the table after {counts.breaks_kept.get(who, 0)}/{breaks} breaks"
        kept = kept if breaks else ""
        print(
            f"    {who:>9}: {shots / g:.1f} shots, {pots / g:.1f} pots ({rate} of tries), "
            f"{counts.fouls.get(who, 0) / g:.2f} fouls, {counts.safeties.get(who, 0) / g:.2f} "
            f"safeties per game{kept}; plan CPU median {1e3 * statistics.median(cpu):.0f} ms, "
            f"max {1e3 * max(cpu):.0f} ms (wall {1e3 * statistics.median(times):.0f} / "
            f"{1e3 * max(times):.0f} ms)"
        )


def match(
    kind: str, strong: str, weak: str, games: int, seed: int, jobs: int, table: str = "9ft"
) -> dict[str, bool]:
    """`games` games of `strong` against `weak` on a `table`, breaks and seats alternating:
    whether `strong` won each, by seed."""
    args = []
    for i in range(games):
        names = (strong, weak) if i % 2 == 0 else (weak, strong)
        args.append((kind, names, (i // 2) % 2, seed + i, table))
    t0 = time.perf_counter()
    results = _map(_game_job, args, jobs)
    stopped = 0
    total = Counts()
    won: dict[str, bool] = {}
    for (_, names, _, game_seed, _), (winner, counts) in zip(args, results, strict=True):
        total.add(counts)
        won[str(game_seed)] = winner is not None and names[winner] == strong
        stopped += winner is None
    wins = sum(won.values())
    print(f"  {kind}: {strong} vs {weak}: {strong} wins {share(wins, games)}", end="")
    print(f"; {stopped} stopped at {MAX_TURNS} turns; {time.perf_counter() - t0:.0f} s")
    report_counts(total, [strong, weak])
    report_chances(total, strong)
    return won


def ladder_steps(text: str) -> tuple[str, ...]:
    """`--steps`: the stronger levels of the ladder's steps to play (not the weakest)."""
    steps = known_names(text, LEVELS[1:], "step (named by its stronger level)")
    if not steps:
        raise argparse.ArgumentTypeError(f"name at least one step: {LEVELS[1:]}")
    return steps


NAMES = {"eight_ball": "8-ball", "nine_ball": "9-ball"}
OPENING = {"eight_ball": "open 8-ball table", "nine_ball": "9-ball rack, no push out"}


def _key(kind: str, part: str) -> str:
    """A part's key in `--save`'s file: 8-ball's plain (the files saved before 9-ball
    was measured), other kinds' prefixed."""
    return part if kind == "eight_ball" else f"{kind} {part}"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--games", type=int, default=200, help="games per comparison")
    parser.add_argument("--runouts", type=int, default=200, help="racks for the runout test")
    parser.add_argument("--only", default="runouts,greedy,ladder")
    parser.add_argument(
        "--kind",
        choices=[*sorted(GAME_BALL), "snooker", "three_cushion"],
        default="eight_ball",
        help="the game of the runouts, the greedy games and the ladder (the goals are "
        "8-ball's); snooker plays frames instead (`bench/snooker.py`), three_cushion "
        "innings and games (`bench/carom.py`)",
    )
    parser.add_argument("--race", type=int, default=5, help="three_cushion: points a game")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--jobs", type=int, default=1, help="worker processes")
    parser.add_argument("--rooms", type=int, default=2, help="computer seats (--only loop)")
    parser.add_argument("--workers", type=int, default=1, help="planner processes (loop)")
    parser.add_argument("--seconds", type=float, default=10.0, help="per mode (loop)")
    parser.add_argument("--configs", type=int, default=1200, help="pots measured (calibrate)")
    parser.add_argument("--fit", action="store_true", help="refit the chance model (calibrate)")
    parser.add_argument("--save", help="write each rack's and game's outcome by seed (JSON)")
    parser.add_argument("--paired", help="compare seed by seed with a file --save wrote")
    parser.add_argument(
        "--noise",
        type=noise_parts,
        default=FULL_NOISE,
        help="the parts of the execution error the runouts' strokes are played with: a "
        "comma list of aim, speed (the cue's, as FastFiz's), tip (the spin's error), "
        "squirt (with tip: the tip's error turns the line too, by its squirt), "
        "ball-speed (with speed: its sigma on the ball's speed), or none (exact "
        "strokes); "
        "the plans assume the level's error (default aim,speed,tip)",
    )
    parser.add_argument(
        "--table",
        choices=TABLES,
        default="9ft",
        help="the table every rack and game is played on (the rooms' is 9ft; fastfiz: "
        "the tournaments' table, 2.236 x 1.116 m, whose balls drop as they cross the "
        "pocket's line, with no jaws)",
    )
    parser.add_argument(
        "--steps",
        type=ladder_steps,
        default=LEVELS[1:],
        help="the ladder's steps to play, each named by its stronger level (a comma list, "
        "e.g. pro: only the pro against the club); all by default",
    )
    args = parser.parse_args(argv)
    parts = set(args.only.split(","))
    if args.kind == "snooker":
        from . import snooker

        return snooker.main(args.games, args.seed, args.jobs, parts, args.steps)
    if args.kind == "three_cushion":
        from . import carom

        return carom.main(
            args.runouts, args.games, args.seed, args.jobs, parts, args.steps, args.race
        )
    outcomes: Outcomes = {}
    before: Outcomes | None = None
    if args.paired:  # read first: a wrong path fails now, not after the games
        with open(args.paired) as earlier:
            before = json.load(earlier)
    print(
        f"bench.ai: levels {', '.join(LEVELS)}; seed {args.seed}; jobs {args.jobs}; "
        f"{args.table} table"
    )
    if "runouts" in parts:
        t0 = time.perf_counter()
        seeds = [args.seed + i for i in range(args.runouts)]
        play = functools.partial(runout, noise=args.noise, table=args.table, kind=args.kind)
        results = _map(play, seeds, args.jobs)
        cleared = sum(ok for ok, _ in results)
        outcomes[_key(args.kind, "runouts")] = {
            str(s): ok for s, (ok, _) in zip(seeds, results, strict=True)
        }
        total = Counts()
        for _, counts in results:
            total.add(counts)
        played = ",".join(args.noise) or "none"
        print(
            f"runouts ({LEVELS[-1]}, ball in hand after a break, {OPENING[args.kind]}; "
            f"strokes played with the error's parts: {played}):"
        )
        print(f"  cleared and won {share(cleared, len(seeds))}; {time.perf_counter() - t0:.0f} s")
        report_counts(total, [LEVELS[-1]])
        report_chances(total, LEVELS[-1])
        ends = sorted(total.ends.items(), key=lambda kv: -kv[1])
        print("  racks not cleared: " + (", ".join(f"{n} {why}" for why, n in ends) or "none"))
        left = sorted(total.left.items(), key=lambda kv: int(kv[0]))
        print(
            f"  racks not cleared, by the balls left to pot (the {GAME_BALL[args.kind]} counted): "
            + (", ".join(f"{n} with {k}" for k, n in left) or "none")
        )
    if "greedy" in parts:
        print(f"against the greedy baseline ({NAMES[args.kind]}, alternating breaks):")
        won = match(args.kind, LEVELS[-1], "greedy", args.games, args.seed, args.jobs, args.table)
        outcomes[_key(args.kind, "greedy")] = won
    if "calibrate" in parts:
        calibrate(args.configs, args.seed, args.fit)
    if "loop" in parts:
        loop_report(args.rooms, args.workers, args.seconds, args.seed)
    if "ladder" in parts:
        print(f"the ladder ({args.kind}, each level against the one below):")
        for weak, strong in itertools.pairwise(LEVELS):
            if strong not in args.steps:
                continue
            won = match(args.kind, strong, weak, args.games, args.seed, args.jobs, args.table)
            outcomes[f"{args.kind} {strong} vs {weak}"] = won
    if args.save:
        with open(args.save, "w") as out:
            json.dump(outcomes, out, indent=1, sort_keys=True)
    if before is not None:
        report_paired(outcomes, before, args.paired)
    return 0


if __name__ == "__main__":
    sys.exit(main())
