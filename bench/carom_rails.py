"""The carom table's rails, ours against pooltool 0.6.0's billiard table.

    python -m bench.carom_rails [--pooltool-python PATH]

pooltool runs in its own interpreter (`--pooltool-python` or $POOLTOOL_PYTHON): its
`BilliardTableSpecs` (2840 x 1420 mm, cushion height 37 mm) and BILLIARD_GENERIC ball
(R 30.75 mm, 210 g, f_c 0.15). A single ball is given a rolling state 0.15 m before a rail:
the speed ratio out / in once it rolls again, straight in; the angle out from the normal for
rolling banks; the speed ratio with running and check english (wz = 1.25 v / R) at 45
degrees. Ours are measured the same way on `Table.carom()` (`tests/engine/test_carom.py`
keeps the figures).
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess

from tests.engine.test_carom import bank

POOLTOOL_SCRIPT = r"""
import json, math, sys
import numpy as np
import pooltool as pt
from pooltool.objects import BilliardTableSpecs
from pooltool.objects.ball.params import BallParams
from pooltool.game.datatypes import GameType

table = pt.Table.from_table_specs(BilliardTableSpecs())
params = BallParams.default(game_type=GameType.THREECUSHION)
R = params.R

def bank(speed, angle_deg, wz_ratio=0.0, gap=0.15):
    # pooltool: x across the width, y along the length; bank into the rail x = 0.
    a = math.radians(angle_deg)
    start = (gap + R, 1.0)
    ball = pt.Ball.create("cue", xy=start)
    ball.params = params
    ball.state.rvw[0] = [start[0], start[1], R]
    v = np.array([-speed * math.cos(a), speed * math.sin(a), 0.0])
    ball.state.rvw[1] = v
    w = np.cross(np.array([0, 0, 1.0]), v) / R
    w[2] = wz_ratio * speed / R
    ball.state.rvw[2] = w
    ball.state.s = pt.constants.sliding if wz_ratio else pt.constants.rolling
    system = pt.System(table=table, balls={"cue": ball}, cue=pt.Cue(cue_ball_id="cue"))
    pt.simulate(system, inplace=True)
    vin = None
    hit = False
    for e in system.events:
        if e.event_type == pt.EventType.BALL_LINEAR_CUSHION and vin is None:
            vin = float(np.linalg.norm(e.agents[0].initial.state.rvw[1]))
            hit = True
        elif hit and e.event_type == pt.EventType.SLIDING_ROLLING:
            out = e.agents[0].final.state.rvw[1]
            angle = math.degrees(math.atan2(abs(out[1]), abs(out[0])))
            return vin, float(np.linalg.norm(out)), angle
    return None

out = {}
out["straight"] = {s: bank(s, 0)[1] / bank(s, 0)[0] for s in (0.5, 1.0, 2.0)}
out["bank"] = {f"{s}/{a}": bank(s, a)[2] for s in (0.8, 1.5) for a in (15, 30, 45, 60)}
r = bank(1.5, 45, 1.25); out["running"] = r[1] / r[0]
r = bank(1.5, 45, -1.25); out["check"] = r[1] / r[0]
print(json.dumps(out))
"""


def ours() -> dict[str, object]:
    straight = {str(s): bank(s, 0) for s in (0.5, 1.0, 2.0)}
    out: dict[str, object] = {"straight": {k: o / i for k, (i, o, _) in straight.items()}}
    out["bank"] = {f"{s}/{a}": bank(s, a)[2] for s in (0.8, 1.5) for a in (15, 30, 45, 60)}
    speed_in, running, _ = bank(1.5, 45, wz=-1.25 * 1.5 / 0.03075)
    _, check, _ = bank(1.5, 45, wz=1.25 * 1.5 / 0.03075)
    out["running"], out["check"] = running / speed_in, check / speed_in
    return out


def pooltool(python: str | None) -> dict[str, object] | None:
    if python is None:
        return None
    done = subprocess.run([python, "-c", POOLTOOL_SCRIPT], capture_output=True, text=True)
    if done.returncode != 0:
        print(done.stderr[-2000:])
        return None
    found: dict[str, object] = json.loads(done.stdout.strip().splitlines()[-1])
    return found


def _rows(figures: dict[str, object]) -> dict[str, float]:
    rows: dict[str, float] = {}
    for key, value in figures.items():
        if isinstance(value, dict):
            rows.update({f"{key} {k}": float(v) for k, v in value.items()})
        else:
            rows[key] = float(value)  # type: ignore[arg-type]
    return rows


def main(argv: list[str] | None = None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--pooltool-python", default=os.environ.get("POOLTOOL_PYTHON"))
    args = parser.parse_args(argv)
    mine, theirs = _rows(ours()), pooltool(args.pooltool_python)
    other = _rows(theirs) if theirs else {}
    print(f"{'figure':<16} {'ours':>9} {'pooltool':>9}")
    for key, value in mine.items():
        print(f"{key:<16} {value:>9.4f} {other.get(key, float('nan')):>9.4f}")


if __name__ == "__main__":
    main()
