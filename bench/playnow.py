"""Play now queue benchmark: what pairing costs the event loop (it runs there, in one step).

    python -m bench.playnow [--players 10000] [--runs 5] [--seed 0]

`--players` players with ratings drawn from N(1500, 300) (seeded) press Play now one after
the other at 1 ms intervals. Prints the median over `--runs` of: the time per join with the
default window (pairing at once included); then, with a window that starts at 0 (so every
one of them is still waiting), the time of one wave over all of them once the windows have
widened by 10 s (to 200), and how many pairs each step made.
"""

from __future__ import annotations

import argparse
import random
import statistics
import time

from server.players import MatchPool, Waiting, Window


def run(players: int, seed: int) -> tuple[float, int, float, int, int]:
    rng = random.Random(seed)
    pool = MatchPool(Window())
    entries = [
        Waiting(f"p{i}", f"P{i}", "eight_ball", rng.gauss(1500, 300), i * 0.001, "key")
        for i in range(players)
    ]
    started = time.perf_counter()
    paired_at_once = sum(pool.join(e) is not None for e in entries)
    join_s = (time.perf_counter() - started) / players
    pool = MatchPool(Window(base=0.0, widen=0.0))
    for e in entries:
        pool.join(e)
    pool.window = Window(base=0.0)
    waiting = len(pool)
    started = time.perf_counter()
    waved = len(pool.pair(now=players * 0.001 + 10.0))
    wave_s = time.perf_counter() - started
    return join_s, paired_at_once, wave_s, waved, waiting


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--players", type=int, default=10_000)
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    results = [run(args.players, args.seed + r) for r in range(args.runs)]
    join_us = statistics.median(r[0] for r in results) * 1e6
    wave_ms = statistics.median(r[2] for r in results) * 1e3
    first = results[0]
    print(f"players: {args.players}, runs: {args.runs} (medians)")
    print(f"join (pairing at once included): {join_us:.1f} us each; {first[1]} pairs at once")
    print(f"wave over {first[4]} waiting after +10 s: {wave_ms:.1f} ms; {first[3]} pairs")


if __name__ == "__main__":
    main()
