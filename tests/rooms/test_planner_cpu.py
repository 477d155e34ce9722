"""The planners' CPU, read from /proc to tell a starved planner from a slow plan: one
reading serves every plan waiting within `CPU_READ_EVERY` (dozens of computer rooms each
read it twice a second), and a later look reads it afresh."""

from __future__ import annotations

import time
from concurrent.futures import ProcessPoolExecutor

from server.rooms.computer import CPU_READ_EVERY, _cpu_seconds


def spin(seconds: float) -> float:
    while time.process_time() < seconds:
        pass
    return time.process_time()


def test_one_reading_serves_the_plans_waiting_together_and_a_later_look_reads_again() -> None:
    with ProcessPoolExecutor(1) as pool:
        pool.submit(spin, 0.0).result()  # the worker is up
        first = _cpu_seconds(pool, now=100.0)
        assert first is not None
        spent = pool.submit(spin, first + 0.3).result()  # the worker's own process time
        assert spent >= first + 0.3
        assert _cpu_seconds(pool, now=100.0 + CPU_READ_EVERY / 2) == first
        later = _cpu_seconds(pool, now=100.0 + CPU_READ_EVERY)
        assert later is not None and later >= first + 0.25  # /proc counts in 1/100 s
        # A clock behind the reading's (another event loop's) reads afresh too.
        pool.submit(spin, spent + 0.3).result()
        again = _cpu_seconds(pool, now=50.0)
        assert again is not None and again >= later + 0.25
