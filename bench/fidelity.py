"""How true the drawn shot is: the web client's playback against the engine's exact balls.

    .venv/bin/python -m bench.fidelity [--breaks 20] [--shots 100] [--seed 1]

For each shot (breaks of fixed racks, then ordinary shots from the tables they left, hit in
random directions, speeds and spins from a seeded generator), the server's real `motion`
message (`plan_shot`, as a room sends it) goes through the client's own playback code under
node (bench/fidelity.mjs: decoded as net.js does, reduced by state.js, played by
playback.js, asked `track(t)`, what `window.pool.track(t)` answers). The reference is the
engine itself, through its public `step`: the shot is run again tick by tick and each tick
is run again from its start up to every instant asked (each contact's exact time, and random
instants), so nothing of the server's tracer is reused to judge it.

Reported, in mm (p50 / p99 / max):
- ball-ball contacts: the drawn gap, | centre distance - 2R | of the two balls at the
  contact's time, and each ball's distance from the engine's position then;
- cushion contacts: the drawn ball's distance to the rail line minus the engine's (how far
  off the rail it is drawn), and its distance from the engine's position;
- pocket drops: the drawn ball at the instant it drops against where the engine drops it;
- away from contacts: every ball on the table at random instants;
- cels: share of drawn sprite cels equal to the engine's at those instants.
Deterministic (fixed seeds): one run gives the figures.
"""

from __future__ import annotations

import argparse
import base64
import json
import math
import subprocess
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from server.engine import (
    BALL_RADIUS,
    DEFAULT_PARAMS,
    DEFAULT_TICK,
    BallSet,
    Shot,
    Table,
    rack,
    simulate,
    step,
    strike,
)
from server.protocol import plan_shot, trace

ROOT = Path(__file__).resolve().parents[1]
NODE_SCRIPT = ROOT / "bench" / "fidelity.mjs"
CELS = 16
RANDOM_INSTANTS = 40  # per shot, away from contacts
BEFORE = 1e-9  # s: the reference stops this short of a contact (a pocket moves the ball)


@dataclass
class Case:
    label: str
    table: Table
    before: BallSet
    shot: Shot
    queries: list[float] = field(default_factory=list)
    kinds: list[tuple] = field(default_factory=list)  # what each query measures


def engine_at(table: Table, before: BallSet, shot: Shot, times: list[float]) -> list[BallSet]:
    """The engine's balls at each time (sorted or not), by `step`: the shot tick by tick,
    each tick run again from its start up to the instants that fall in it."""
    state = before.copy()
    strike(state, shot, DEFAULT_PARAMS)
    order = sorted(range(len(times)), key=lambda i: times[i])
    out: list[BallSet | None] = [None] * len(times)
    k = 0
    tick = 0
    while k < len(order):
        t0 = tick * DEFAULT_TICK
        while k < len(order) and times[order[k]] <= t0 + DEFAULT_TICK:
            span = times[order[k]] - t0 - BEFORE
            at = state.copy()
            if span > 0:
                step(table, at, span, t0)
            out[order[k]] = at
            k += 1
        moving = bool(np.any((state.states == 2) | (state.states == 3)))  # sliding, rolling
        if not moving:
            while k < len(order):  # at rest: the balls stay where they are
                out[order[k]] = state.copy()
                k += 1
            break
        step(table, state, DEFAULT_TICK, t0)
        tick += 1
    return [s for s in out if s is not None]


def cases(breaks: int, shots: int, seed: int) -> list[Case]:
    table = Table.pool("9ft")
    rng = np.random.default_rng(seed)
    found: list[Case] = []
    tables: list[BallSet] = []
    for i in range(breaks):
        balls = rack("eight_ball", table, seed=seed * 1000 + i)
        shot = Shot(float(rng.normal(0, 0.004)), float(rng.uniform(8.0, 11.0)))
        found.append(Case(f"break {i}", table, balls, shot))
        tables.append(simulate(table, balls, shot).final)
    i = 0
    while len(found) < breaks + shots:
        balls = tables[i % len(tables)].copy()
        if not balls.on_table[balls.index(0)]:  # the cue ball went down: rack again
            fresh = rack("eight_ball", table, seed=seed * 1000 + breaks + i)
            tables[i % len(tables)] = simulate(table, fresh, Shot(0.0, 9.0)).final
            i += 1
            continue
        shot = Shot(
            float(rng.uniform(-math.pi, math.pi)),
            float(rng.uniform(0.5, 6.0)),
            (float(rng.uniform(-0.3, 0.3)), float(rng.uniform(-0.35, 0.35))),
        )
        found.append(Case(f"shot {i}", table, balls, shot))
        tables[i % len(tables)] = simulate(table, balls, shot).final
        i += 1
    return found


def measure(case: Case, rng: np.random.Generator) -> tuple[str, dict]:
    """The motion message, and what to ask the client and the engine."""
    result = simulate(case.table, case.before, case.shot)
    plan = plan_shot(result, trace(case.table, case.before, case.shot), 1, 6)
    for event in result.events:
        if event.kind == "ball":
            case.kinds.append(("ball", event.ids))
        elif event.kind == "cushion":
            case.kinds.append(("cushion", event.ids, event.target))
        elif event.kind == "pocket":
            case.kinds.append(("pocket", event.ids))
        else:
            continue
        case.queries.append(event.time)
    for t in rng.uniform(0, result.duration, RANDOM_INSTANTS):
        case.kinds.append(("free",))
        case.queries.append(float(t))
    return base64.b64encode(plan.motion).decode("ascii"), {
        "bytes": len(plan.motion),
        "duration": result.duration,
    }


def rail_distance(cushion: np.ndarray, x: float, y: float) -> float:
    """Signed distance of (x, y) from a cushion's line, into the table."""
    return (x - cushion[0]) * cushion[4] + (y - cushion[1]) * cushion[5]


def pct(values: list[float]) -> str:
    if not values:
        return "      -       -       -"
    a = np.array(values) * 1000
    return f"{np.percentile(a, 50):7.3f} {np.percentile(a, 99):7.3f} {a.max():7.3f}"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--breaks", type=int, default=20)
    parser.add_argument("--shots", type=int, default=100)
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    started = time.perf_counter()
    rng = np.random.default_rng(args.seed + 7)
    all_cases = cases(args.breaks, args.shots, args.seed)
    payload = []
    sizes = []
    for case in all_cases:
        motion, info = measure(case, rng)
        payload.append({"motion": motion, "times": case.queries})
        sizes.append(info)
    drawn = json.loads(
        subprocess.run(
            ["node", str(NODE_SCRIPT)],
            input=json.dumps({"cases": payload}),
            capture_output=True,
            text=True,
            check=True,
        ).stdout
    )["cases"]
    cushions = all_cases[0].table.cushion_array()
    r = BALL_RADIUS
    ball_gap, ball_err, rail_gap, rail_err, drop_err, free_err = [], [], [], [], [], []
    cels_same = cels_all = 0
    for case, shown in zip(all_cases, drawn, strict=True):
        exact = engine_at(case.table, case.before, case.shot, case.queries)
        for kind, engine, balls in zip(case.kinds, exact, shown, strict=True):
            at = {row[0]: row for row in balls}

            def error(ball: int, engine: BallSet = engine, at: dict = at) -> float:
                row = at.get(ball)
                if row is None:
                    return math.inf  # not drawn at all
                x, y = engine.positions[engine.index(ball)]
                return math.hypot(row[1] - x, row[2] - y)

            if kind[0] == "ball":
                a, b = kind[1]
                if a in at and b in at:
                    ball_gap.append(
                        abs(math.hypot(at[a][1] - at[b][1], at[a][2] - at[b][2]) - 2 * r)
                    )
                ball_err.extend([error(a), error(b)])
            elif kind[0] == "cushion":
                ball, rail = kind[1][0], kind[2]
                x, y = engine.positions[engine.index(ball)]
                if ball in at:
                    drawn_d = rail_distance(cushions[rail], at[ball][1], at[ball][2])
                    rail_gap.append(abs(drawn_d - rail_distance(cushions[rail], x, y)))
                rail_err.append(error(ball))
            elif kind[0] == "pocket":
                drop_err.append(error(kind[1][0]))
            else:
                for ball in engine.ids[engine.on_table].tolist():
                    free_err.append(error(ball))
                    row = at.get(ball)
                    if row is not None:
                        cels_all += 1
                        cels_same += row[3] == int(engine.cels()[engine.index(ball)])
    breaks = [s for c, s in zip(all_cases, sizes, strict=True) if c.label.startswith("break")]
    others = [s for c, s in zip(all_cases, sizes, strict=True) if not c.label.startswith("break")]
    print(
        f"{len(breaks)} breaks and {len(others)} ordinary shots "
        f"(seed {args.seed}, {time.perf_counter() - started:.0f} s)"
    )
    print(f"{'what (mm)':<38} {'count':>6} {'p50':>7} {'p99':>7} {'max':>7}")
    rows = [
        ("ball-ball contact: drawn gap", ball_gap),
        ("ball-ball contact: ball vs engine", ball_err),
        ("cushion contact: off the rail", rail_gap),
        ("cushion contact: ball vs engine", rail_err),
        ("pocket drop: ball vs engine", drop_err),
        ("away from contacts: ball vs engine", free_err),
    ]
    for name, values in rows:
        print(f"{name:<38} {len(values):>6} {pct(values)}")
    print(f"cels drawn as the engine's: {100 * cels_same / max(1, cels_all):.2f} % of {cels_all}")
    for name, group in (("breaks", breaks), ("ordinary shots", others)):
        total = sum(s["bytes"] for s in group)
        seconds = sum(s["duration"] for s in group)
        print(
            f"motion message, {name}: {total / len(group):.0f} B a shot, "
            f"{total / seconds:.0f} B/s of shot (before WebSocket framing)"
        )


if __name__ == "__main__":
    main()
