"""An outage's errors are logged once, then once a minute with a count: a server whose
Redis is down for a while (its heartbeat failing twice a second here) does not log the
same warning or traceback at every beat (without the filter: 16 heartbeat warnings, 9 of
the inbox's and 8 Play now tracebacks in 8 s)."""

from __future__ import annotations

import re
import time
from collections import Counter

import pytest

from tests.support.redis import RedisServer

from .servers import ServerSet

pytestmark = [pytest.mark.timeout(120), pytest.mark.redis, pytest.mark.postgres, pytest.mark.slow]
OUTAGE = 8.0  # s: sixteen heartbeats


def problems(text: str) -> Counter[str]:
    """Warning and error lines, their numbers blanked (a delay, a count, a port)."""
    lines = [line for line in text.splitlines() if line.startswith(("WARNING:", "ERROR:"))]
    return Counter(re.sub(r"\d+(\.\d+)?", "N", line) for line in lines)


def test_a_redis_outage_logs_each_error_once(servers, redis: RedisServer) -> None:
    group: ServerSet = servers(1)
    (server,) = group.all
    before = len(server.output())
    redis.stop()
    time.sleep(OUTAGE)
    redis.start()
    time.sleep(2.0)
    seen = problems(server.output()[before:])
    assert seen, "the outage was not logged at all"
    assert max(seen.values()) == 1, seen.most_common(3)
