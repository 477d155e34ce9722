"""`python -m bench.load` reports the CPU its server's computer planners took (the server's
child processes), read from /proc: a child that has used CPU is counted, a process that is
not a child is not."""

from __future__ import annotations

import os
import subprocess
import sys

from bench.load import children_cpu_seconds, cpu_seconds

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
