"""Snooker pocket acceptance, ours against pooltool 0.6.0's "Generic Snooker" pockets.

    python -m bench.pockets [--pooltool-python PATH] [--speeds 0.6,1.5,4.0]

A single ball is given a rolling state 0.5 m before the middle of a pocket's mouth; the
window is the largest offset (mm, 1 mm steps, each side) across the line of approach at
which it still drops into that pocket: straight into a corner, along the rail into a corner
(offset from the rail), and into a middle pocket at 90, 60 and 30 degrees to the rail.
pooltool runs in its own interpreter (`--pooltool-python` or $POOLTOOL_PYTHON; see
`scripts/pooltool-venv`) on a 3569 x 1778 mm table with its snooker pockets and ball; the
figures in `tests/engine/test_snooker.py` come from here.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess

import numpy as np

from server.engine import MotionState, Table
from tests.support.rolling import roll

POOLTOOL_SCRIPT = r"""
import json, math, sys
import numpy as np
import pooltool as pt
from pooltool.objects import SnookerTableSpecs
from pooltool.objects.ball.params import BallParams
from pooltool.game.datatypes import GameType

speeds = [float(s) for s in sys.argv[1].split(",")]
# pooltool's Generic Snooker pockets (pooltool/objects/table/collection.py), WPBSA size.
specs = SnookerTableSpecs(l=3.569, w=1.778, cushion_width=1.55*25.4/1000, cushion_height=0.028,
    corner_pocket_width=0.083, corner_pocket_angle=0, corner_pocket_depth=0.036,
    corner_pocket_radius=0.043, corner_jaw_radius=3.6*25.4/1000,
    side_pocket_width=0.075, side_pocket_angle=0, side_pocket_depth=0.95*25.4/1000,
    side_pocket_radius=1.68*25.4/1000, side_jaw_radius=2.5*25.4/1000)
table = pt.Table.from_table_specs(specs)
params = BallParams.default(game_type=GameType.SNOOKER)
R = params.R

def drops(start, u, speed, pocket):
    ball = pt.Ball.create("cue", xy=start)
    ball.params = params
    ball.state.rvw[0] = [start[0], start[1], R]
    v = np.array([u[0], u[1], 0.0]) * speed
    ball.state.rvw[1] = v
    ball.state.rvw[2] = np.cross(np.array([0, 0, 1.0]), v) / R
    ball.state.s = pt.constants.rolling
    system = pt.System(table=table, balls={"cue": ball}, cue=pt.Cue(cue_ball_id="cue"))
    pt.simulate(system, inplace=True)
    return any(e.event_type == pt.EventType.BALL_POCKET and e.ids[1] == pocket
               for e in system.events)

def window(mouth, u, speed, pocket, sign):
    across = np.array([-u[1], u[0]])
    last = mm = 0
    while mm <= 120 and mm <= last + 10:
        if drops(mouth - 0.5 * u + sign * mm / 1000 * across, u, speed, pocket):
            last = mm
        mm += 1
    return last

# pooltool's x runs across the width, y along the length: its table is ours reflected.
out = {"R": R}
d = 1 / math.sqrt(2)
a = 0.083 / math.sqrt(2)
for speed in speeds:
    out[f"corner_{speed}"] = [window(np.array([a / 2, a / 2]), np.array([-d, -d]), speed, "lb", s)
                              for s in (1, -1)]
    last = 0
    for mm in range(80):
        if drops(np.array([R + mm / 1000, 0.5]), np.array([0.0, -1.0]), speed, "lb"):
            last = mm
        elif mm > last + 10:
            break
    out[f"rail_{speed}"] = last
    for ang in (90, 60, 30):
        t = math.radians(ang)
        u = np.array([-math.sin(t), -math.cos(t)])
        out[f"side_{ang}_{speed}"] = [window(np.array([0.0, specs.l / 2]), u, speed, "lc", s)
                                      for s in (1, -1)]
print(json.dumps(out))
"""


def _drops(table: Table, name: str, start: np.ndarray, u: np.ndarray, speed: float) -> bool:
    balls, _ = roll(table, start, u, speed)
    index = next(k for k, p in enumerate(table.pockets) if p.name == name)
    return bool(balls.states[0] == MotionState.POCKETED and balls.pockets[0] == index)


def _window(table: Table, name: str, u: np.ndarray, speed: float, sign: int) -> int:
    pocket = next(p for p in table.pockets if p.name == name)
    mouth = (np.array(pocket.jaws[0]) + np.array(pocket.jaws[1])) / 2
    across = np.array([-u[1], u[0]])
    last = mm = 0
    while mm <= 120 and mm <= last + 10:
        if _drops(table, name, mouth - 0.5 * u + sign * mm / 1000 * across, u, speed):
            last = mm
        mm += 1
    return last


def ours(speeds: list[float]) -> dict[str, object]:
    """The same windows on `Table.snooker()`."""
    table = Table.snooker()
    r = table.ball_radius
    out: dict[str, object] = {"R": r}
    corner = np.array(table.pockets[0].outward)
    for speed in speeds:
        out[f"corner_{speed}"] = [_window(table, "bottom_left", corner, speed, s) for s in (1, -1)]
        last = 0
        for mm in range(80):
            start = np.array([0.5, r + mm / 1000])
            if _drops(table, "bottom_left", start, np.array([-1.0, 0.0]), speed):
                last = mm
            elif mm > last + 10:
                break
        out[f"rail_{speed}"] = last
        for angle in (90, 60, 30):
            a = math.radians(angle)
            u = np.array([-math.cos(a), -math.sin(a)])
            out[f"side_{angle}_{speed}"] = [
                _window(table, "bottom_side", u, speed, s) for s in (1, -1)
            ]
    return out


def pooltool(speeds: list[float], python: str | None) -> dict[str, object] | None:
    if python is None:
        return None
    arg = ",".join(str(s) for s in speeds)
    done = subprocess.run(
        [python, "-c", POOLTOOL_SCRIPT, arg], capture_output=True, text=True, timeout=3600
    )
    if done.returncode != 0:
        print(done.stderr[-2000:])
        return None
    found: dict[str, object] = json.loads(done.stdout.strip().splitlines()[-1])
    return found


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--pooltool-python", default=os.environ.get("POOLTOOL_PYTHON"))
    parser.add_argument("--speeds", default="0.6,1.5,4.0")
    args = parser.parse_args(argv)
    speeds = [float(s) for s in args.speeds.split(",")]
    mine = ours(speeds)
    theirs = pooltool(speeds, args.pooltool_python)
    print(f"{'window (mm)':<16} {'ours':>12} {'pooltool':>12}")
    for key, value in mine.items():
        other = theirs.get(key, "-") if theirs else "-"
        print(f"{key:<16} {value!s:>12} {other!s:>12}")


if __name__ == "__main__":
    main()
