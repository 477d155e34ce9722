"""Running a process on CPU time nobody else wants (Linux's `SCHED_IDLE` class).

Used where a process must never slow the rooms' event loop and shot threads: the
computer's planners, and a benchmark's flood standing in for clients on other machines.
`nice 19` was not enough on 2 cores: a niced process still makes its core look
busy, so the kernel woke the rooms' shot threads on the event loop's core, where they waited
behind the loop. A core running only idle-class work counts as free. The price: while
work at normal priority keeps every core busy, an idle-class process gets no CPU at all,
so whoever waits on one watches how much CPU it gets (`process_stat`).
"""

from __future__ import annotations

import os
from pathlib import Path

FALLBACK_NICE = 19  # where the idle class is missing (not Linux)


def run_when_idle() -> None:
    """Put this process in the idle scheduling class (or at nice 19 without one)."""
    try:
        os.sched_setscheduler(0, os.SCHED_IDLE, os.sched_param(0))
    except (AttributeError, OSError):
        os.nice(FALLBACK_NICE)


def process_stat(pid: int, thread: int | None = None) -> tuple[int, float] | None:
    """(parent pid, user + system CPU seconds of all its threads) of process `pid`, or of
    its one thread `thread` (a native thread id), from Linux's /proc; None when it cannot
    be read (the process ended, or no /proc)."""
    path = f"/proc/{pid}/stat" if thread is None else f"/proc/{pid}/task/{thread}/stat"
    try:
        fields = Path(path).read_text().rsplit(")", 1)[1].split()
        return int(fields[1]), (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")
    except (OSError, IndexError, ValueError):
        return None
