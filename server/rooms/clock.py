"""Where rooms read the time and the rack seeds from, so tests can fix both.

Production uses the system's clocks and secret random seeds; a test passes a `Clock` it
moves by hand and a `SeedSource` that deals the same racks every run, and then asserts exact
outcomes instead of branching on whatever the rack happened to be.
"""

from __future__ import annotations

import itertools
import secrets
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field


@dataclass(frozen=True)
class Clock:
    """`wall()`: seconds since the epoch (shown to people, stored); `monotonic()`: for
    measuring how long something idled."""

    wall: Callable[[], float] = time.time
    monotonic: Callable[[], float] = time.monotonic


SYSTEM_CLOCK = Clock()


class SeedSource:
    """Rack seeds for new rooms: secret random ones, or `fixed(...)` ones in order."""

    def __init__(self, seeds: Iterator[int] | None = None) -> None:
        self._seeds = seeds

    @classmethod
    def fixed(cls, *seeds: int) -> SeedSource:
        """These seeds in turn, again from the first when they run out."""
        return cls(itertools.cycle(seeds))

    def next(self) -> int:
        if self._seeds is None:
            return secrets.randbelow(2**31)
        return next(self._seeds)


@dataclass
class ManualClock:
    """A clock a test moves by hand (`advance`)."""

    now: float = 1_000_000.0
    ticks: float = 0.0
    clock: Clock = field(init=False)

    def __post_init__(self) -> None:
        self.clock = Clock(wall=lambda: self.now, monotonic=lambda: self.ticks)

    def advance(self, seconds: float) -> None:
        self.now += seconds
        self.ticks += seconds
