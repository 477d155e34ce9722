"""`python -m bench.load`: the CPU its server's computer planners took (the server's child
processes), read from /proc: a child that has used CPU is counted, a process that is not a
child is not; the loop's CPU, its main thread's alone; and which shots' starts are
timed."""

from __future__ import annotations

import math
import os
import subprocess
import sys

import pytest

from bench.load import Stats, children_cpu_seconds, cpu_seconds

# Spins until it has used 0.3 s of CPU, says so, then waits (not using CPU) to be released.
SPIN = (
    "import sys, time\n"
    "while time.process_time() < 0.3: pass\n"
    "print('spun', flush=True)\n"
    "sys.stdin.read()\n"
)


def test_the_cpu_of_a_child_process_is_counted_and_only_a_childs() -> None:
    before = children_cpu_seconds(os.getpid())
    child = subprocess.Popen(
        [sys.executable, "-c", SPIN], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True
    )
    try:
        assert child.stdout is not None and child.stdout.readline() == "spun\n"
        used = children_cpu_seconds(os.getpid()) - before
        assert used >= 0.25, used  # /proc counts in clock ticks (1/100 s)
        assert cpu_seconds(child.pid) >= 0.25
        # Only a parent counts a process: the child, which started none, counts nothing.
        assert children_cpu_seconds(child.pid) == 0.0
    finally:
        assert child.stdin is not None
        child.stdin.close()
        child.wait(timeout=30)


# The same spin in a second thread, while the main thread waits.
SPIN_ASIDE = (
    "import sys, threading, time\n"
    "def spin():\n"
    "    while time.thread_time() < 0.3: pass\n"
    "threading.Thread(target=spin).start()\n"
    "for t in threading.enumerate():\n"
    "    if t is not threading.current_thread(): t.join()\n"
    "print('spun', flush=True)\n"
    "sys.stdin.read()\n"
)


@pytest.mark.parametrize(("program", "on_the_loop"), [(SPIN, True), (SPIN_ASIDE, False)])
def test_the_loops_cpu_is_the_main_threads_alone(program: str, on_the_loop: bool) -> None:
    child = subprocess.Popen(
        [sys.executable, "-c", program], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True
    )
    try:
        assert child.stdout is not None and child.stdout.readline() == "spun\n"
        assert cpu_seconds(child.pid) >= 0.25
        loop = cpu_seconds(child.pid, thread=child.pid)
        assert loop >= 0.25 if on_the_loop else loop < 0.15, loop
    finally:
        assert child.stdin is not None
        child.stdin.close()
        child.wait(timeout=30)


def test_a_start_is_timed_only_for_a_shot_struck_inside_the_window() -> None:
    """A shot struck before the window whose motion comes inside it carried the benchmark's
    own pauses into the figures; one struck inside whose motion comes after is timed."""
    stats = Stats()
    stats.motion_came(sent=1.0, now=1.05, duration=1.0)  # before any window
    stats.opened = 10.0
    stats.motion_came(sent=9.9, now=10.3, duration=1.0)  # struck before the window
    stats.motion_came(sent=10.0, now=10.02, duration=1.0)
    stats.motion_came(sent=math.nan, now=10.5, duration=1.0)  # struck by nobody here
    stats.closed = 30.0
    stats.motion_came(sent=29.99, now=30.2, duration=0.5)  # its motion after the window
    stats.motion_came(sent=30.0, now=30.01, duration=1.0)  # struck after
    assert stats.starts == pytest.approx([0.02, 0.21])
    assert stats.motions == 2
    # 120 ticks in hand; of 60, the motion came 0.11 s late: 14 ticks (13.2) were due before.
    assert (stats.ticks, stats.in_hand) == (180, 120 + 60 - 14)
