"""The quick tier's guard: a helper that starts Redis, PostgreSQL, Chromium or a server
process refuses to run inside a test that does not carry the matching marker."""

from __future__ import annotations

import pytest

from tests.support.tiers import MARKERS, QUICK, needs


def test_an_unmarked_test_may_not_start_an_expensive_service() -> None:
    for marker in MARKERS:
        with pytest.raises(RuntimeError, match=rf"pytest\.mark\.{marker}"):
            needs(marker)


def test_a_marked_test_may(request: pytest.FixtureRequest) -> None:
    request.node.add_marker(pytest.mark.postgres)
    needs("postgres")
    with pytest.raises(RuntimeError):
        needs("redis")


def test_an_unknown_marker_is_a_mistake() -> None:
    with pytest.raises(ValueError, match="unknown"):
        needs("gpu")


def test_the_quick_tier_leaves_every_marker_out() -> None:
    assert QUICK == "not browser and not redis and not postgres and not slow"
