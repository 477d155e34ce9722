"""Which database: a SQLite file (the default, nothing to install) or PostgreSQL (the shared
history of several processes), as one SQLAlchemy engine; and which errors are passing.

SQLite runs with the driver's own transactions off: the repository says `BEGIN IMMEDIATE`
before a write, so a write takes the file's lock first (and waits out another process's
lock at once, not halfway through), and `BEGIN` before a read, so a read sees one state.
WAL journal with `synchronous=NORMAL`: a crash loses at most the last few writes, never
the database.
"""

from __future__ import annotations

import sqlite3
from pathlib import Path
from typing import Any

from sqlalchemy import Engine, create_engine, event
from sqlalchemy.engine import URL, make_url
from sqlalchemy.exc import DBAPIError, OperationalError
from sqlalchemy.pool import NullPool


def database_url(target: Path | str) -> URL:
    """The URL of `target`: a path is a SQLite file; `postgresql://` means psycopg 3."""
    if isinstance(target, Path) or "://" not in target:
        return URL.create("sqlite", database=str(target))
    url = make_url(target)
    if url.drivername in ("postgresql", "postgres"):
        url = url.set(drivername="postgresql+psycopg")
    if url.drivername not in ("postgresql+psycopg", "sqlite", "sqlite+pysqlite"):
        raise ValueError(f"unsupported database {url.drivername!r}: postgresql:// or a path")
    return url


def make_engine(url: URL) -> Engine:
    """An engine for the store's one thread (it holds one connection at a time)."""
    if url.get_backend_name() == "sqlite":
        path = url.database
        if path and path != ":memory:":
            Path(path).parent.mkdir(parents=True, exist_ok=True)
        engine = create_engine(url, poolclass=NullPool)
        event.listen(engine, "connect", _sqlite_setup)
        return engine
    given = set(url.query)
    connect_args = {k: v for k, v in POSTGRES_TIMEOUTS.items() if k not in given}
    return create_engine(
        url, pool_size=1, max_overflow=0, pool_pre_ping=True, connect_args=connect_args
    )


# A database behind a network cut answers nothing: without these a connect or a query
# would wait for the kernel's TCP timeouts (minutes) before the retry loop could try again.
# The URL may set its own (`?connect_timeout=...`).
POSTGRES_TIMEOUTS: dict[str, int] = {
    "connect_timeout": 5,  # s
    "keepalives": 1,
    "keepalives_idle": 5,  # s of silence before probing
    "keepalives_interval": 2,
    "keepalives_count": 3,
    "tcp_user_timeout": 10_000,  # ms a sent request may stay unacknowledged
}


def _sqlite_setup(dbapi_connection: Any, _record: Any) -> None:
    dbapi_connection.isolation_level = None  # transactions are begun by the repository
    dbapi_connection.execute("PRAGMA journal_mode = WAL")
    dbapi_connection.execute("PRAGMA synchronous = NORMAL")
    dbapi_connection.execute("PRAGMA foreign_keys = ON")


def is_transient(exc: BaseException) -> bool:
    """Worth trying again: another process holds the SQLite file, or PostgreSQL cannot be
    reached (restarting, network) or dropped the connection. Not a bad statement."""
    if not isinstance(exc, DBAPIError):
        return False
    if exc.connection_invalidated:
        return True
    if isinstance(exc.orig, sqlite3.OperationalError):
        text = str(exc.orig)
        return "locked" in text or "busy" in text
    return isinstance(exc, OperationalError)
