"""Bring a database to the newest schema with Alembic (`migrations/`), on either backend.

A SQLite file from before Alembic counted its migrations in `PRAGMA user_version`; the
first two Alembic revisions are those same migrations, so such a file is stamped with the
matching revision and upgraded from there, keeping every row. On PostgreSQL an advisory
lock lets only one of several starting processes migrate; the others then find it done.
To change the schema, add a revision at the end of `migrations/versions/` (and change
`schema.py` to match: the store tests compare the two).
"""

from __future__ import annotations

from functools import cache
from pathlib import Path

from alembic import command
from alembic.config import Config
from alembic.runtime.migration import MigrationContext
from alembic.script import ScriptDirectory
from sqlalchemy import Connection, inspect, text

MIGRATIONS = Path(__file__).with_name("migrations")
_LOCK = 0x706F6F6C  # "pool": the advisory lock key of the migration on PostgreSQL


@cache
def _config() -> Config:
    config = Config()
    config.set_main_option("script_location", str(MIGRATIONS))
    config.set_main_option("path_separator", "os")
    return config


@cache
def head() -> str:
    """The newest revision."""
    found = ScriptDirectory.from_config(_config()).get_current_head()
    assert found is not None
    return found


def current(connection: Connection) -> str | None:
    """The revision the database is at (None: no Alembic stamp yet)."""
    return MigrationContext.configure(connection).get_current_revision()


def upgrade(connection: Connection) -> str:
    """Migrate inside the caller's open transaction; returns the revision reached."""
    if connection.dialect.name == "postgresql":
        connection.execute(text("SELECT pg_advisory_xact_lock(:key)"), {"key": _LOCK})
    revision = current(connection)
    if revision == head():
        return revision
    config = _config()
    config.attributes["connection"] = connection
    try:
        if revision is None and connection.dialect.name == "sqlite":
            before = connection.exec_driver_sql("PRAGMA user_version").scalar()
            if before and inspect(connection).has_table("matches"):
                command.stamp(config, f"{int(before):04d}")
        command.upgrade(config, "head")
    finally:
        config.attributes.pop("connection", None)
    return head()
