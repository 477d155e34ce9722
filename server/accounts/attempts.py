"""Failed sign-in attempts, limited per address and per account name (`limits`, moving
windows): guessing one account's password from many addresses, or many accounts' from one,
is slowed alike; signing in right does not count. A name that has no account is counted
like one, so the limit tells nothing either. Counted in this process (like the other
per-client quotas): a cluster of N processes allows up to N times as many, still bounded."""

from __future__ import annotations

from limits import parse
from limits.storage import MemoryStorage
from limits.strategies import MovingWindowRateLimiter


class SignInLimits:
    def __init__(self, per_address: str, per_account: str) -> None:
        self._limiter = MovingWindowRateLimiter(MemoryStorage())
        self._address = parse(per_address)
        self._account = parse(per_account)

    def allow(self, address: str, name_key: str) -> bool:
        """May this address try this name now (neither is over its failures)?"""
        return self._limiter.test(self._address, "sign-in address", address) and self._limiter.test(
            self._account, "sign-in account", name_key
        )

    def failed(self, address: str, name_key: str) -> None:
        """Count a wrong answer against both."""
        self._limiter.hit(self._address, "sign-in address", address)
        self._limiter.hit(self._account, "sign-in account", name_key)

    def allow_address(self, address: str) -> bool:
        """Count one attempt that names no account (a passkey's)."""
        return self._limiter.hit(self._address, "sign-in address", address)
