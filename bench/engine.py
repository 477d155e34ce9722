"""Engine benchmark: a full 8-ball break simulated to rest, frames included.

    python -m bench.engine [--runs 30] [--seed 0] [--pooltool-python PATH]

Prints the median wall time of `simulate` (cue ball on the head spot, 10 m/s straight at
the apex, centre hit) and of `settle` (the same ticks without the frames, as the computer's
search runs them) with ticks and events, over `--runs` runs after one warm-up call
(whose time, the numba compile or cache load, is printed too); then both doors' mean time
a shot over 1,000 strokes like those the search tries, then the same strokes with the cue
raised (10-60 degrees: swerves, masses and jumps). When pooltool is importable,
or an interpreter that has it is named by `--pooltool-python` (or $POOLTOOL_PYTHON),
pooltool simulates the same break in the same run and the ratio is printed.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import statistics
import subprocess
import sys
import time
from collections.abc import Callable

import numpy as np

from server.engine import (
    CUE,
    ENGINE_VERSION,
    TICK_HZ,
    BallSet,
    Shot,
    Table,
    rack,
    settle,
    simulate,
    tip_seen_level,
)

SEARCH_SHOTS = 1000

POOLTOOL_SCRIPT = r"""
import json, statistics, sys, time
import numpy as np
import pooltool as pt

runs = int(sys.argv[1])
target_speed = float(sys.argv[2])

def make():
    table = pt.Table.default()
    balls = pt.get_rack(pt.GameType.EIGHTBALL, table, spacing_factor=1e-3)
    system = pt.System(table=table, balls=balls, cue=pt.Cue(cue_ball_id="cue"))
    return system

def cue_speed(V0):
    s = make()
    s.strike(V0=V0, phi=pt.aim.at_ball(s, "1"))
    pt.simulate(s, inplace=True, max_events=3)
    for ev in s.events:
        if ev.event_type == pt.EventType.STICK_BALL:
            return float(np.linalg.norm(ev.agents[1].final.state.rvw[1]))
    raise SystemExit("no stick-ball event")

# Find the stick speed that gives the cue ball `target_speed` (bisection; it is linear).
V0 = target_speed * target_speed / cue_speed(target_speed)
t0 = time.perf_counter()
s = make(); s.strike(V0=V0, phi=pt.aim.at_ball(s, "1")); pt.simulate(s, inplace=True)
warm = time.perf_counter() - t0
sim, cont, events, duration = [], [], [], []
for _ in range(runs):
    s = make()
    s.strike(V0=V0, phi=pt.aim.at_ball(s, "1"))
    t0 = time.perf_counter(); pt.simulate(s, inplace=True); t1 = time.perf_counter()
    pt.continuize(s, dt=1 / 120, inplace=True); t2 = time.perf_counter()
    sim.append(t1 - t0); cont.append(t2 - t1); events.append(len(s.events)); duration.append(s.t)
print(json.dumps({"version": pt.__version__, "warm_s": warm, "V0": V0,
                  "cue_speed": cue_speed(V0), "sim_ms": statistics.median(sim) * 1e3,
                  "continuize_ms": statistics.median(cont) * 1e3,
                  "events": statistics.median(events), "seconds": statistics.median(duration)}))
"""


def ours(runs: int, seed: int) -> dict:
    table = Table.pool("9ft")
    balls = rack("eight_ball", table, seed=seed)
    shot = Shot(0.0, 10.0)
    t0 = time.perf_counter()
    simulate(table, balls, shot)
    warm = time.perf_counter() - t0
    times = []
    result = None
    for _ in range(runs):
        t0 = time.perf_counter()
        result = simulate(table, balls, shot)
        times.append(time.perf_counter() - t0)
    assert result is not None
    return {
        "settle_ms": per_shot_ms(settle, [(table, balls, shot)], runs),
        "warm_s": warm,
        "median_ms": statistics.median(times) * 1e3,
        "min_ms": min(times) * 1e3,
        "max_ms": max(times) * 1e3,
        "ticks": len(result.frames),
        "events": len(result.events),
        "seconds": result.duration,
        "pocketed": result.pocketed(),
    }


def search_shots(count: int, seed: int, raised: bool = False) -> list[tuple[Table, BallSet, Shot]]:
    """Strokes like those the computer's search tries: from tables left by a break, any
    direction, 0.5-5 m/s, tip within 0.3 R; `raised`: the same with the cue raised 10-60
    degrees (the tip then within 0.3 R seen along the cue)."""
    rng = np.random.default_rng(seed)
    table = Table.pool("9ft")
    shots: list[tuple[Table, BallSet, Shot]] = []
    rack_seed = 0
    while len(shots) < count:
        broken = simulate(table, rack("eight_ball", table, seed=rack_seed), Shot(0.0, 10.0)).final
        rack_seed += 1
        if CUE not in broken.on_table_ids():
            continue
        for _ in range(min(50, count - len(shots))):
            tip = (float(rng.uniform(-0.3, 0.3)), float(rng.uniform(-0.3, 0.3)))
            angle, speed = float(rng.uniform(-math.pi, math.pi)), float(rng.uniform(0.5, 5.0))
            if raised:
                elevation = math.radians(float(rng.uniform(10.0, 60.0)))
                shot = Shot(angle, speed, tip_seen_level(tip, elevation), elevation)
            else:
                shot = Shot(angle, speed, tip)
            shots.append((table, broken, shot))
    return shots


def per_shot_ms(run: Callable[..., object], shots: list, runs: int) -> float:
    """Median over `runs` passes (after one warm-up shot) of the mean time a shot, in ms."""
    run(*shots[0])
    times = []
    for _ in range(runs):
        t0 = time.perf_counter()
        for shot in shots:
            run(*shot)
        times.append((time.perf_counter() - t0) / len(shots))
    return statistics.median(times) * 1e3


def pooltool(runs: int, python: str | None) -> dict | None:
    interpreter = python
    if interpreter is None:
        try:
            import pooltool  # noqa: F401
        except ImportError:
            return None
        interpreter = sys.executable
    out = subprocess.run(
        [interpreter, "-c", POOLTOOL_SCRIPT, str(runs), "10.0"],
        capture_output=True,
        text=True,
        timeout=900,
    )
    if out.returncode != 0:
        print(out.stderr[-2000:], file=sys.stderr)
        return None
    return json.loads(out.stdout.strip().splitlines()[-1])


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", type=int, default=30)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--pooltool-python", default=os.environ.get("POOLTOOL_PYTHON"))
    args = parser.parse_args(argv)
    r = ours(args.runs, args.seed)
    print(
        f"engine {ENGINE_VERSION}: 8-ball break, 10 m/s centre hit at the apex, "
        f"seed {args.seed}, {args.runs} runs"
    )
    print(f"  first call (numba compile or cache load): {r['warm_s'] * 1e3:.0f} ms")
    print(
        f"  simulate to rest, frames included: median {r['median_ms']:.2f} ms "
        f"(min {r['min_ms']:.2f}, max {r['max_ms']:.2f})"
    )
    print(f"  settle to rest, no frames (the search's door): median {r['settle_ms']:.2f} ms")
    print(
        f"  {r['ticks']} ticks of 1/{TICK_HZ} s ({r['seconds']:.2f} s of play), "
        f"{r['events']} events, pocketed {r['pocketed']}"
    )
    shots = search_shots(SEARCH_SHOTS, args.seed)
    print(
        f"  {SEARCH_SHOTS} strokes like the search's (tables left by a break, 0.5-5 m/s): "
        f"simulate {per_shot_ms(simulate, shots, 5):.3f} ms a shot, "
        f"settle {per_shot_ms(settle, shots, 5):.3f} ms (median of 5 passes)"
    )
    raised = search_shots(SEARCH_SHOTS, args.seed, raised=True)
    print(
        f"  the same strokes with the cue raised 10-60 degrees: "
        f"simulate {per_shot_ms(simulate, raised, 5):.3f} ms a shot, "
        f"settle {per_shot_ms(settle, raised, 5):.3f} ms (median of 5 passes)"
    )
    pt = pooltool(max(5, args.runs // 2), args.pooltool_python)
    if pt is None:
        print(
            "pooltool: not installed (scripts/pooltool-venv,"
            " then --pooltool-python .venv-pooltool/bin/python)"
        )
        return
    total = pt["sim_ms"] + pt["continuize_ms"]
    print(
        f"pooltool {pt['version']}: same break (stick speed {pt['V0']:.2f} m/s gives the cue "
        f"ball {pt['cue_speed']:.2f} m/s), first call {pt['warm_s']:.1f} s"
    )
    print(
        f"  simulate median {pt['sim_ms']:.2f} ms + continuize at 1/120 s "
        f"{pt['continuize_ms']:.2f} ms = {total:.2f} ms; {pt['events']:.0f} events, "
        f"{pt['seconds']:.2f} s of play"
    )
    print(
        f"  ratio pooltool / ours: {total / r['median_ms']:.1f}x "
        f"(simulate only: {pt['sim_ms'] / r['median_ms']:.1f}x)"
    )


if __name__ == "__main__":
    main()
