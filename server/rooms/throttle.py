"""`Throttle`: a message that may be asked for in bursts, sent at most once an interval."""

from __future__ import annotations

import asyncio
import math
from collections.abc import Callable


class Throttle:
    """Calls `send` at most once every `interval` seconds of loop time: the requests of a
    burst after the first are summed up in one trailing call. `interval` 0: every request
    calls at once. Once stopped, it never calls again."""

    def __init__(self, interval: float, send: Callable[[], None]) -> None:
        self.interval = interval
        self._send = send
        self._timer: asyncio.TimerHandle | None = None
        self._last = -math.inf
        self._stopped = False

    def request(self) -> None:
        if self.interval <= 0:
            self._fire()
            return
        if self._timer is not None:
            return  # a trailing call is already due
        loop = asyncio.get_running_loop()
        wait = self._last + self.interval - loop.time()
        if wait > 0:
            self._timer = loop.call_later(wait, self._fire)
            return
        self._fire()

    def stop(self) -> None:
        self._stopped = True
        if self._timer is not None:
            self._timer.cancel()

    def _fire(self) -> None:
        self._timer = None
        if self._stopped:
            return
        if self.interval > 0:
            self._last = asyncio.get_running_loop().time()
        self._send()
