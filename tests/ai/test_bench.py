"""`python -m bench.ai`'s paired comparison: a saved run replays seed for seed, and the
report counts the seeds only one version won."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from bench.ai import _map, main, sign_test


def test_the_sign_test_is_the_two_sided_binomial_tail() -> None:
    assert sign_test(0, 0) == 1.0
    assert sign_test(4, 4) == 1.0
    assert sign_test(8, 0) == pytest.approx(2 / 256)
    assert sign_test(0, 8) == pytest.approx(2 / 256)
    # 25 against 12 discordant seeds: p = 2 * P(X <= 12), X ~ Binomial(37, 1/2).
    assert sign_test(25, 12) == pytest.approx(0.04703, abs=1e-5)


def test_a_saved_run_replays_seed_for_seed_and_the_report_counts_differences(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    first, second = tmp_path / "first.json", tmp_path / "second.json"
    args = ["--runouts", "2", "--seed", "3", "--only", "runouts"]
    main([*args, "--save", str(first)])
    saved = json.loads(first.read_text())
    assert sorted(saved["runouts"]) == ["3", "4"]
    # Pretend the earlier version lost seed 3 whatever it did: a rack won only now when
    # this run clears it, a difference of nothing otherwise.
    flipped = {"runouts": {**saved["runouts"], "3": not saved["runouts"]["3"]}}
    first.write_text(json.dumps(flipped))
    capsys.readouterr()
    main([*args, "--save", str(second), "--paired", str(first)])
    assert json.loads(second.read_text()) == saved  # the same seeds, the same outcomes
    report = capsys.readouterr().out
    now_only, then_only = (1, 0) if saved["runouts"]["3"] else (0, 1)
    assert f"won only now {now_only}, only then {then_only};" in report
    assert "of 2;" in report


def test_the_carom_benchmark_finds_the_engine_corrected_aims_drop_more(
    capsys: pytest.CaptureFixture[str],
) -> None:
    from bench.caroms import main as caroms

    caroms(["--tables", "80", "--seed", "0"])
    report = capsys.readouterr().out
    match = re.search(r"geometry's aim (\d+)%, corrected (\d+)%", report)
    assert match is not None, report
    raw, corrected = int(match.group(1)), int(match.group(2))
    assert corrected > raw + 20  # the secant of engine shots finds the aims that drop
    strokes = re.search(r"(\d+) strokes", report)
    assert strokes is not None and int(strokes[1]) > 30


def _kernels_compiled(_: int) -> bool:
    from server.ai import geometry

    return bool(geometry._pot_kernel.signatures) and bool(geometry._open_kernel.signatures)


def test_each_worker_loads_the_compiled_kernels_before_its_first_job() -> None:
    """A worker's first plan would otherwise count numba's compiling in the plan time."""
    assert _map(_kernels_compiled, [0, 1], jobs=2) == [True, True]
