"""Waiting for something another thread or process does, with a bound instead of a sleep."""

from __future__ import annotations

import time
from collections.abc import Callable


def until(
    check: Callable[[], object],
    within: float = 30.0,
    what: str | Callable[[], str] = "not within the time",
) -> None:
    """Return once `check()` is true; fail with `what` if it is not within `within` s
    (`what()` when it is a function: a message made at the time, such as a log's end)."""
    deadline = time.monotonic() + within
    while not check():
        assert time.monotonic() < deadline, what() if callable(what) else what
        time.sleep(0.1)
