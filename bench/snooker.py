"""The computer at snooker: the pro's self-play frames (highest break per frame, centuries),
the ladder of levels frame by frame, and how long a plan takes.

    python -m bench.ai --kind snooker [--games 10] [--only frames,ladder] [--seed 0]
                       [--jobs 1] [--steps pro]

Every stroke is played with the striker's own execution error (`Bot.execute`; the pro's is
FastFiz's: sigma aim 0.125 deg, speed 0.075 m/s, tip 0.5 mm). A frame is cut at
`MAX_TURNS` turns and then decided on points. `--games` is the number of frames of the
self-play and of each ladder step; each frame alternates the break-off.
"""

from __future__ import annotations

import itertools
import statistics
import time
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from server.ai import Bot
from server.ai.levels import LEVELS
from server.ai.play import play_turn
from server.rules import Game

from .ai import _map  # each worker warmed up first, as a room's planner is

MAX_TURNS = 400  # a frame longer than this is decided on points (a stalemate guard)
SLOWEST = 3  # the slowest plans printed, with what they searched


@dataclass
class FrameRecord:
    """One frame: the winner (by seat), each seat's highest break, the plan times (s)."""

    winner: int | None
    points: tuple[int, ...]
    highest: tuple[int, ...]
    plans: dict[int, list[float]] = field(default_factory=dict)
    cut: bool = False
    slowest: list[tuple[float, int, str]] = field(default_factory=list)  # (s, sims, what)


def play_frame(levels: tuple[str, str], seed: int) -> FrameRecord:
    """A frame between `levels` (by seat), seat `seed % 2` breaking off."""
    game = Game.new("snooker", list(levels), breaker=seed % 2, seed=seed)
    bots = [Bot(level, seed * 2 + k) for k, level in enumerate(levels)]
    rng = np.random.default_rng(seed)
    plans: dict[int, list[float]] = {0: [], 1: []}
    turns = 0
    slowest: list[tuple[float, int, str]] = []
    while not game.over and turns < MAX_TURNS:
        seat = game.decision.seat if game.decision else game.turn
        in_hand = " from the D" if game.ball_in_hand and not game.decision else ""
        t0 = time.process_time()
        turn = bots[seat].plan(game, seat)
        plans[seat].append(time.process_time() - t0)
        what = f"{turn.decision or turn.kind}{in_hand}, {len(game.balls.on_table_ids())} balls"
        slowest = sorted([*slowest, (plans[seat][-1], bots[seat].last_sims, what)])[-SLOWEST:]
        play_turn(game, seat, turn, bots[seat], rng)
        turns += 1
    score = game.score
    assert score is not None
    points = score.points
    winner = game.winner
    if winner is None and points[0] != points[1]:
        winner = 0 if points[0] > points[1] else 1
    return FrameRecord(winner, points, score.highest_break, plans, not game.over, slowest)


def _job(args: tuple[tuple[str, str], int]) -> FrameRecord:
    return play_frame(*args)


def self_play(frames: int, seed: int, jobs: int, level: str = "pro") -> None:
    t0 = time.perf_counter()
    records = _map(_job, [((level, level), seed + k) for k in range(frames)], jobs)
    best = [max(r.highest) for r in records]
    plans = [t for r in records for seat in r.plans.values() for t in seat]
    print(f"self-play, {level} against {level}, {frames} frames:")
    print(
        f"  highest break per frame: mean {statistics.mean(best):.1f}, median "
        f"{statistics.median(best):.0f}, max {max(best)}; centuries {sum(b >= 100 for b in best)}"
    )
    print(f"  frames cut at {MAX_TURNS} turns: {sum(r.cut for r in records)}")
    print(
        f"  plan time (CPU s): median {statistics.median(plans):.2f}, "
        f"p95 {np.percentile(plans, 95):.2f}, max {max(plans):.2f} over {len(plans)} plans; "
        f"{time.perf_counter() - t0:.0f} s"
    )
    slow = sorted(p for r in records for p in r.slowest)[-SLOWEST:]
    said = "; ".join(f"{t:.2f} s, {sims} simulations ({what})" for t, sims, what in reversed(slow))
    print(f"  slowest plans: {said}")


def ladder(frames: int, seed: int, jobs: int, steps: Sequence[str]) -> None:
    print(f"the ladder (snooker frames, each level against the one below, {frames} frames):")
    for weak, strong in itertools.pairwise(LEVELS):
        if strong not in steps:
            continue
        args = [((strong, weak) if k % 2 == 0 else (weak, strong), seed + k) for k in range(frames)]
        records = _map(_job, args, jobs)
        won = sum(
            1
            for k, r in enumerate(records)
            if r.winner is not None and r.winner == (0 if k % 2 == 0 else 1)
        )
        print(f"  {strong} beat {weak} in {won} of {frames} frames ({100 * won / frames:.0f} %)")


def main(frames: int, seed: int, jobs: int, parts: set[str], steps: Sequence[str]) -> int:
    if "frames" in parts or "runouts" in parts:
        self_play(frames, seed, jobs)
    if "ladder" in parts:
        ladder(frames, seed, jobs, steps)
    return 0
