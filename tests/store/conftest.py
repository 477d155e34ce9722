"""Every store test runs on both backends: a SQLite file and a private PostgreSQL (one
server for the session, a fresh database per test)."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

from server.store import Database
from tests.support.postgres import PostgresServer, postgres  # noqa: F401  (the fixture)


@pytest.fixture(params=["sqlite", pytest.param("postgresql", marks=pytest.mark.postgres)])
def target(request: pytest.FixtureRequest, tmp_path: Path) -> str | Path:
    """Where a test's store is: a SQLite path or a PostgreSQL URL (an empty database)."""
    if request.param == "sqlite":
        return tmp_path / "billiards.db"
    server: PostgresServer = request.getfixturevalue("postgres")
    return server.create_database()


@pytest.fixture
def db(target: str | Path) -> Iterator[Database]:
    database = Database(target)
    yield database
    database.close()
