"""Running a process on CPU time nobody else wants (Linux's `SCHED_IDLE` class).

Used where a process must never slow the rooms' event loop and shot threads: the
computer's planners, and a benchmark's flood standing in for clients on other machines.
`nice 19` was not enough on this 2-core machine: a niced process still makes its core look
busy, so the kernel woke the rooms' shot threads on the event loop's core, where they waited
behind the loop. A core running only idle-class work counts as free.
"""

from __future__ import annotations

import os

FALLBACK_NICE = 19  # where the idle class is missing (not Linux)


def run_when_idle() -> None:
    """Put this process in the idle scheduling class (or at nice 19 without one)."""
    try:
        os.sched_setscheduler(0, os.SCHED_IDLE, os.sched_param(0))
    except (AttributeError, OSError):
        os.nice(FALLBACK_NICE)
