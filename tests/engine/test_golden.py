"""Golden results: fixed shots whose outcome is pinned bit for bit, like a chess engine's perft.

Each case records its ticks, its events (counted by kind), the balls pocketed in order and
digests of the events and of the final `BallSet`; `data/golden.json` also records the
`ENGINE_VERSION` that produced them. Any change to what the physics does fails here, and a
stored shot must then not be replayed by the new engine as if nothing happened: the
version has to change too.

To accept a deliberate change (after bumping `PHYSICS_REVISION` in server/engine/version.py
when no parameter changed):

    .venv/bin/python -m tests.engine.test_golden --update

Without `--update` it prints the differences. `--update` refuses to record changed results
under an unchanged `ENGINE_VERSION`.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import math
import sys
from collections.abc import Mapping
from dataclasses import dataclass
from functools import cache
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from server.codec import to_data
from server.engine import (
    DEFAULT_TICK,
    ENGINE_VERSION,
    BallSet,
    EventKind,
    Settled,
    Shot,
    ShotResult,
    Table,
    rack,
    settle,
    simulate,
)

GOLDEN = Path(__file__).parent / "data" / "golden.json"
COMMAND = ".venv/bin/python -m tests.engine.test_golden --update"

# One position for the ordinary shots: ball 2 sits straight in line from the cue ball to
# the top-right corner (angle pi/4), the others are targets for banks, kicks and cuts.
POSITION: dict[int, tuple[float, float]] = {
    0: (1.70, 0.43),
    1: (1.00, 0.90),
    2: (2.30, 1.03),
    3: (2.10, 0.25),
    4: (0.60, 0.30),
    5: (1.27, 1.10),
    9: (0.35, 0.75),
}


@dataclass(frozen=True)
class Case:
    """A shot on a 9ft table: from a seeded rack (cue ball on the head spot unless `cue`
    moves it), or from `POSITION`."""

    name: str
    shot: Shot
    game: str | None = None
    seed: int = 0
    cue: tuple[float, float] | None = None

    def balls(self, table: Table) -> BallSet:
        if self.game is None:
            return BallSet.place(POSITION)
        balls = rack(self.game, table, self.seed)
        return balls if self.cue is None else balls.with_ball(0, self.cue)

    def definition(self) -> dict[str, Any]:
        return {
            "game": self.game,
            "seed": self.seed if self.game is not None else None,
            "cue": list(self.cue) if self.cue is not None else None,
            "position": None
            if self.game is not None
            else {str(k): list(v) for k, v in POSITION.items()},
            "shot": to_data(self.shot),
        }


STRAIGHT = math.pi / 4

CASES: tuple[Case, ...] = (
    Case("break_8_seed0_10ms", Shot(0.0, 10.0), "eight_ball", 0),
    Case("break_8_seed1_12ms_draw", Shot(0.0, 12.0, (0.0, -0.2)), "eight_ball", 1),
    Case("break_8_seed2_6ms_side", Shot(0.25, 6.0, (0.2, 0.2)), "eight_ball", 2, (0.60, 0.30)),
    Case("break_9_seed0_10ms", Shot(0.0, 10.0), "nine_ball", 0),
    Case("break_9_seed3_8ms_left", Shot(0.0, 8.0, (-0.3, 0.0)), "nine_ball", 3),
    Case("break_9_seed4_11ms_side", Shot(0.28, 11.0), "nine_ball", 4, (0.58, 0.25)),
    Case("straight_in", Shot(STRAIGHT, 1.2)),
    Case("stun_in", Shot(STRAIGHT, 4.0, (0.0, -0.3))),
    Case("follow_scratch", Shot(STRAIGHT, 2.5, (0.0, 0.4))),
    Case("soft_touch", Shot(-0.42, 0.5)),
    Case("bank_off_rail", Shot(-1.2, 3.0)),
    Case("kick_nine", Shot(2.3, 3.0)),
    Case("masse_side", Shot(2.0, 4.0, (-0.45, 0.2))),
    Case("power_cut", Shot(2.55, 7.0, (0.3, -0.1))),
)


def state_digest(balls: BallSet) -> str:
    """sha256 of the final arrays (ids, positions, velocities, spins, states, phases,
    pockets in that order), each as float64 little-endian (the integers are exact there)."""
    h = hashlib.sha256()
    for name in ("ids", "positions", "velocities", "spins", "states", "phases", "pockets"):
        h.update(np.ascontiguousarray(getattr(balls, name), dtype="<f8").tobytes())
    return h.hexdigest()


def events_digest(result: ShotResult | Settled) -> str:
    """sha256 of every event as float64 little-endian (time, speed, kind code, ids, target)."""
    codes = {kind.value: i for i, kind in enumerate(EventKind)}
    rows = [
        [e.time, e.speed, codes[e.kind], e.ids[0], e.ids[1] if len(e.ids) > 1 else -1, e.target]
        for e in result.events
    ]
    return hashlib.sha256(np.asarray(rows, dtype="<f8").reshape(-1, 6).tobytes()).hexdigest()


def measure(case: Case) -> dict[str, Any]:
    table = Table.pool("9ft")
    result = simulate(table, case.balls(table), case.shot)
    kinds = [e.kind for e in result.events]
    return {
        "ticks": len(result.frames),
        "events": len(result.events),
        "by_kind": {kind.value: kinds.count(kind.value) for kind in EventKind},
        "pocketed": result.pocketed(),
        "stalled_ticks": result.stalled_ticks,
        "events_digest": events_digest(result),
        "final_digest": state_digest(result.final),
    }


@cache
def current() -> dict[str, Any]:
    """The golden file's contents as this engine produces them."""
    return {
        "engine_version": ENGINE_VERSION,
        "cases": {
            case.name: {"definition": case.definition(), "result": measure(case)} for case in CASES
        },
    }


def recorded() -> dict[str, Any]:
    data: dict[str, Any] = json.loads(GOLDEN.read_text())
    return data


def changed_results(old: Mapping[str, Any], new: Mapping[str, Any]) -> list[str]:
    """One line per differing value of the cases both files define the same way."""
    lines = []
    for name, case in new["cases"].items():
        before = old["cases"].get(name)
        if before is None or before["definition"] != case["definition"]:
            continue
        for key, value in case["result"].items():
            was = before["result"].get(key)
            if was != value:
                lines.append(f"  {name}.{key}: recorded {_short(was)}, now {_short(value)}")
    return lines


def _short(value: Any) -> str:
    """A digest's first 12 digits (enough to tell two apart), any other value as is."""
    return value[:12] + "…" if isinstance(value, str) and len(value) == 64 else repr(value)


def changed_cases(old: Mapping[str, Any], new: Mapping[str, Any]) -> list[str]:
    """One line per case added, removed or defined differently."""
    lines = []
    for name in old["cases"].keys() - new["cases"].keys():
        lines.append(f"  {name}: removed")
    for name, case in new["cases"].items():
        before = old["cases"].get(name)
        if before is None:
            lines.append(f"  {name}: new")
        elif before["definition"] != case["definition"]:
            lines.append(f"  {name}: definition changed")
    return lines


def test_the_golden_cases_are_the_recorded_ones() -> None:
    lines = changed_cases(recorded(), current())
    assert not lines, "the golden cases differ from data/golden.json:\n" + "\n".join(
        [*lines, f"regenerate with: {COMMAND}"]
    )


def test_the_physics_gives_the_golden_results() -> None:
    old, new = recorded(), current()
    lines = changed_results(old, new)
    if not lines:
        return
    if old["engine_version"] == new["engine_version"]:
        advice = (
            f"the physics changed but ENGINE_VERSION did not ({ENGINE_VERSION}). If the "
            "change is deliberate, bump PHYSICS_REVISION in server/engine/version.py, then "
            f"regenerate with: {COMMAND}"
        )
    else:
        advice = (
            f"ENGINE_VERSION changed ({old['engine_version']} -> {ENGINE_VERSION}). If the "
            f"change is deliberate, regenerate with: {COMMAND}"
        )
    raise AssertionError("golden results changed:\n" + "\n".join(lines) + "\n" + advice)


@pytest.mark.parametrize("case", CASES, ids=lambda case: case.name)
def test_settling_without_frames_gives_the_golden_results(case: Case) -> None:
    """`settle` (the search's door) runs the same ticks as `simulate` without recording
    frames: the recorded results hold for it too, bit for bit."""
    table = Table.pool("9ft")
    settled = settle(table, case.balls(table), case.shot)
    want = recorded()["cases"][case.name]["result"]
    assert events_digest(settled) == want["events_digest"]
    assert state_digest(settled.final) == want["final_digest"]
    assert settled.stalled_ticks == want["stalled_ticks"]
    assert settled.duration == want["ticks"] * DEFAULT_TICK


def test_the_golden_file_records_this_engine_version() -> None:
    version = recorded()["engine_version"]
    assert version == ENGINE_VERSION, (
        f"data/golden.json was made by engine {version}, this is {ENGINE_VERSION}; "
        f"regenerate with: {COMMAND}"
    )


def pretty(value: Any, indent: str = "") -> str:
    """JSON with one value per line, except containers short enough to read on one line."""
    flat = json.dumps(value, separators=(", ", ": "))
    if not isinstance(value, dict | list) or len(indent) + len(flat) <= 90:
        return flat
    inner = indent + " "
    if isinstance(value, list):
        items = [inner + pretty(v, inner) for v in value]
        return "[\n" + ",\n".join(items) + "\n" + indent + "]"
    items = [f"{inner}{json.dumps(k)}: {pretty(v, inner)}" for k, v in value.items()]
    return "{\n" + ",\n".join(items) + "\n" + indent + "}"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(
        prog="python -m tests.engine.test_golden", description=__doc__.splitlines()[0]
    )
    parser.add_argument("--update", action="store_true", help="rewrite data/golden.json")
    args = parser.parse_args(argv)
    new = current()
    old = recorded() if GOLDEN.exists() else {"engine_version": None, "cases": {}}
    cases, results = changed_cases(old, new), changed_results(old, new)
    same_version = old["engine_version"] == new["engine_version"]
    for title, lines in (("cases:", cases), ("results:", results)):
        if lines:
            print(title, *lines, sep="\n")
    if not cases and not results and same_version:
        print(f"golden results unchanged (engine {ENGINE_VERSION})")
        return 0
    if not args.update:
        print(f"engine {old['engine_version']} recorded, {ENGINE_VERSION} now; --update rewrites")
        return 1
    if results and same_version:
        print(
            "refused: results changed under the same ENGINE_VERSION; bump PHYSICS_REVISION in "
            "server/engine/version.py first",
            file=sys.stderr,
        )
        return 1
    GOLDEN.write_text(pretty(new) + "\n")
    print(f"wrote {GOLDEN} (engine {ENGINE_VERSION})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
