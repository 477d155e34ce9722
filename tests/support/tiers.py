"""The test tiers: every test that starts Chromium, Redis, PostgreSQL or a server process
carries the marker that says so, and `scripts/test --quick` leaves those out.

The helpers that start such things call `needs(marker)`: inside a test without that
marker it fails at once, so a forgotten marker cannot slip an expensive test into the
quick tier. Outside a test (a benchmark using the same helpers) it checks nothing.
"""

from __future__ import annotations

import pytest

MARKERS = {
    "browser": "drives a headless Chromium",
    "redis": "starts a private redis-server",
    "postgres": "starts a private PostgreSQL server",
    "slow": "starts server processes, or runs for many seconds",
}
QUICK = " and ".join(f"not {name}" for name in MARKERS)  # the `-m` of `--quick`

_current: pytest.Item | None = None


def entering(item: pytest.Item | None) -> None:
    """The test now being set up, run or torn down (None between tests)."""
    global _current
    _current = item


def needs(marker: str) -> None:
    """Fail unless the running test carries `marker` (see the module's docstring)."""
    if marker not in MARKERS:
        raise ValueError(f"unknown test marker {marker!r}")
    item = _current
    if item is not None and item.get_closest_marker(marker) is None:
        raise RuntimeError(
            f"{item.nodeid} {MARKERS[marker]} but is not marked `@pytest.mark.{marker}`"
            " (scripts/test --quick would run it)"
        )
