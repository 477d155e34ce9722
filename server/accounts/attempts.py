"""Failed sign-in attempts, limited per address and per account name (`limits`, moving
windows): guessing one account's password from many addresses, or many accounts' from one,
is slowed alike; signing in right does not count. A name that has no account is counted
like one, so the limit tells nothing either. Counted in this process (like the other
per-client quotas): a cluster of N processes allows up to N times as many, still bounded.

An attempt reserves its place before its password is hashed (`reserve`) and gives it back
when answered (`release`, counted if it failed), so a burst sent at once is refused beyond
the limit as if sent one after another. The hashing itself takes its `turn()`: a process
runs `CONCURRENT` at once (each takes a core and 64 MiB)."""

from __future__ import annotations

import asyncio
from collections import Counter

from limits import RateLimitItem, parse
from limits.storage import MemoryStorage
from limits.strategies import MovingWindowRateLimiter

CONCURRENT = 2  # password checks at once


class SignInLimits:
    def __init__(self, per_address: str, per_account: str) -> None:
        self._turns = asyncio.Semaphore(CONCURRENT)
        self._limiter = MovingWindowRateLimiter(MemoryStorage())
        self._address = parse(per_address)
        self._account = parse(per_account)
        self._in_flight: Counter[tuple[str, str]] = Counter()

    def turn(self) -> asyncio.Semaphore:
        """`async with limits.turn():` around a password's hashing."""
        return self._turns

    def _left(self, item: RateLimitItem, kind: str, who: str) -> int:
        remaining = self._limiter.get_window_stats(item, kind, who).remaining
        return remaining - self._in_flight[kind, who]

    def reserve(self, address: str, name_key: str) -> bool:
        """May this address try this name now (counting the attempts still in flight)?
        If so, the attempt holds a place until `release`."""
        if self._left(self._address, "address", address) <= 0:
            return False
        if self._left(self._account, "account", name_key) <= 0:
            return False
        self._in_flight["address", address] += 1
        self._in_flight["account", name_key] += 1
        return True

    def release(self, address: str, name_key: str, failed: bool) -> None:
        for kind, who, item in (
            ("address", address, self._address),
            ("account", name_key, self._account),
        ):
            self._in_flight[kind, who] -= 1
            if not self._in_flight[kind, who]:
                del self._in_flight[kind, who]
            if failed:
                self._limiter.hit(item, kind, who)

    def allow_address(self, address: str) -> bool:
        """Count one request that names no account (a passkey's options)."""
        return self._limiter.hit(self._address, "passkey", address)
