"""ENGINE_VERSION names the physics: it is stable, and any number that changes a result
changes it."""

from __future__ import annotations

import math
import os
import re
import subprocess
import sys
from dataclasses import fields, replace
from pathlib import Path

from server.engine import (
    DEFAULT_PARAMS,
    DEFAULT_TICK,
    ENGINE_VERSION,
    PHYSICS_REVISION,
    TICK_HZ,
    PhysicsParams,
    engine_version,
)


def test_the_version_is_the_defaults_digest() -> None:
    assert engine_version(DEFAULT_PARAMS, DEFAULT_TICK) == ENGINE_VERSION
    assert engine_version(PhysicsParams(), 1.0 / 120) == ENGINE_VERSION
    assert re.fullmatch(rf"{PHYSICS_REVISION}\+[0-9a-f]{{12}}", ENGINE_VERSION)


def test_the_tick_is_the_tick_rate() -> None:
    assert TICK_HZ == 120
    assert DEFAULT_TICK == 1 / TICK_HZ


def test_the_digest_is_stable() -> None:
    assert engine_version(DEFAULT_PARAMS, DEFAULT_TICK) == engine_version(
        PhysicsParams(), DEFAULT_TICK
    )


def test_every_parameter_changes_the_version() -> None:
    names = [f.name for f in fields(PhysicsParams)]
    seen = {ENGINE_VERSION}
    for name in names:
        value = getattr(DEFAULT_PARAMS, name)
        seen.add(engine_version(replace(DEFAULT_PARAMS, **{name: value * 1.5 + 1})))
    assert len(seen) == 1 + len(names)


def test_a_one_ulp_change_changes_the_version() -> None:
    nudged = replace(DEFAULT_PARAMS, g=math.nextafter(DEFAULT_PARAMS.g, math.inf))
    assert engine_version(nudged) != ENGINE_VERSION


def test_the_tick_and_the_revision_change_the_version() -> None:
    assert engine_version(DEFAULT_PARAMS, 1 / 240) != ENGINE_VERSION
    other = engine_version(DEFAULT_PARAMS, DEFAULT_TICK, PHYSICS_REVISION + 1)
    assert other != ENGINE_VERSION
    assert other.startswith(f"{PHYSICS_REVISION + 1}+")


def test_the_kernels_values_decide_so_an_int_and_its_float_agree() -> None:
    assert engine_version(replace(DEFAULT_PARAMS, g=10)) == engine_version(
        replace(DEFAULT_PARAMS, g=10.0)
    )


def test_another_process_computes_the_same_version() -> None:
    code = "from server.engine import ENGINE_VERSION; print(ENGINE_VERSION)"
    env = {**os.environ, "PYTHONHASHSEED": "12345"}
    out = subprocess.run(
        [sys.executable, "-c", code],
        capture_output=True,
        text=True,
        check=True,
        env=env,
        cwd=Path(__file__).parents[2],
    )
    assert out.stdout.strip() == ENGINE_VERSION
