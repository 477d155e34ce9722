"""Several real `python -m server` processes sharing a private Redis and one database: the
cluster as it runs in production, on free loopback ports (helpers in `servers`, `sockets`
and `takeover`)."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from pathlib import Path

import pytest

from tests.support.postgres import PostgresServer, postgres  # noqa: F401  (a fixture)
from tests.support.redis import RedisServer, redis  # noqa: F401  (a fixture)

from .servers import Server, ServerSet


@pytest.fixture
def servers(
    redis: RedisServer,  # noqa: F811
    postgres: PostgresServer,  # noqa: F811
    tmp_path: Path,
) -> Iterator[Callable[..., ServerSet]]:
    """`servers(n, store="postgres", **settings)`: n processes on this test's Redis and a
    fresh PostgreSQL database (`store="sqlite"`: one SQLite file in the test's folder),
    every room racked with `settings["rack_seed"]`; all stopped at the end."""
    started: list[Server] = []

    def start(n: int, store: str = "postgres", **settings: object) -> ServerSet:
        if store == "postgres":
            settings["database_url"] = postgres.create_database()
        group = ServerSet.start(n, redis.url, tmp_path, settings)
        started.extend(group.all)
        return group

    yield start
    for server in started:
        server.stop()
