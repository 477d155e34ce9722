"""`python -m bench.farm`: its baseline, Glicko-2 without the farm rule, is the audit's farm
(25 wins over new players took a rating from 1500 to 2134)."""

from __future__ import annotations

import pytest

from bench.farm import glicko_alone


def test_glicko2_alone_gives_the_audits_farm_its_634_points() -> None:
    assert glicko_alone(25) == pytest.approx(634, abs=1)
