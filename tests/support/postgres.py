"""A private PostgreSQL for tests and benchmarks: `initdb` into a temporary folder, started
with `pg_ctl` on a free port (socket in that folder too), removed afterwards. Never a
server that merely happens to be running.

PostgreSQL refuses to run as root, so as root (CI, the containers here) every server
command runs as the `postgres` user (`runuser`), whose folder it then is. The binaries are
Debian's (`/usr/lib/postgresql/<version>/bin`, the newest there), or `pg_ctl` on PATH.

    with running_postgres() as pg:          # a benchmark, a script
        url = pg.create_database()          # postgresql://postgres@127.0.0.1:port/db_1

    def test_x(postgres: PostgresServer):   # pytest: one server for the session
        url = postgres.create_database()    # a fresh, empty database per test
"""

from __future__ import annotations

import contextlib
import itertools
import os
import shutil
import subprocess
import tempfile
from collections.abc import Iterator
from pathlib import Path

import pytest

from tests.support.tiers import needs

from .ports import free_port

USER = "postgres"


def binaries() -> Path:
    """The folder of `initdb` and `pg_ctl`: the newest Debian version, else PATH's."""
    versions = sorted(
        Path("/usr/lib/postgresql").glob("*/bin/pg_ctl"),
        key=lambda p: int(p.parent.parent.name) if p.parent.parent.name.isdigit() else 0,
    )
    if versions:
        return versions[-1].parent
    found = shutil.which("pg_ctl")
    if found is None:
        raise RuntimeError("PostgreSQL is not installed (scripts/test installs it)")
    return Path(found).parent


class PostgresServer:
    """One private server. `durable=False` (tests) turns off fsync: faster, and nothing
    here must survive a crash of the machine."""

    def __init__(self, durable: bool = False) -> None:
        self.bin = binaries()
        self.as_root = os.geteuid() == 0
        self.folder = Path(tempfile.mkdtemp(prefix="pool-pg-"))
        self.data = self.folder / "data"
        self.log = self.folder / "server.log"
        self.port = free_port()
        self.durable = durable
        self._names = itertools.count(1)
        if self.as_root:
            shutil.chown(self.folder, USER, USER)
        self._run(
            "initdb",
            "-D",
            str(self.data),
            "-U",
            USER,
            "--auth=trust",
            "-E",
            "UTF8",
            "--locale=C",
            *(() if durable else ("--no-sync",)),
        )

    def _run(self, program: str, *args: str) -> str:
        command = [str(self.bin / program), *args]
        if self.as_root:
            command = ["runuser", "-u", USER, "--", *command]
        done = subprocess.run(command, capture_output=True, text=True, timeout=120)
        if done.returncode != 0:
            raise RuntimeError(f"{program} failed: {done.stdout}{done.stderr}{self.server_log()}")
        return done.stdout

    def server_log(self) -> str:
        return self.log.read_text(errors="replace")[-3000:] if self.log.exists() else ""

    @property
    def url(self) -> str:
        """The URL of the `postgres` database (for creating others)."""
        return self.database_url("postgres")

    def database_url(self, name: str) -> str:
        return f"postgresql://{USER}@127.0.0.1:{self.port}/{name}"

    def start(self) -> None:
        """Start (again, on the same port and data: a restart keeps every row)."""
        options = f"-p {self.port} -k {self.folder} -c listen_addresses=127.0.0.1"
        if not self.durable:
            options += " -c fsync=off -c full_page_writes=off"
        self._run("pg_ctl", "-D", str(self.data), "-l", str(self.log), "-o", options, "-w", "start")

    def stop(self, mode: str = "fast") -> None:
        """Stop (`immediate`: like a crash, connections cut, nothing flushed)."""
        self._run("pg_ctl", "-D", str(self.data), "-m", mode, "-w", "stop")

    def running(self) -> bool:
        return (self.data / "postmaster.pid").exists()

    def create_database(self, name: str | None = None) -> str:
        """A new empty database; returns its URL."""
        name = name or f"db_{next(self._names)}"
        self._run("createdb", "-h", str(self.folder), "-p", str(self.port), "-U", USER, name)
        return self.database_url(name)

    def remove(self) -> None:
        with contextlib.suppress(Exception):
            if self.running():
                self.stop("immediate")
        shutil.rmtree(self.folder, ignore_errors=True)


@contextlib.contextmanager
def running_postgres(durable: bool = False) -> Iterator[PostgresServer]:
    """A started private server, stopped and removed on leaving."""
    needs("postgres")
    server = PostgresServer(durable=durable)
    try:
        server.start()
        yield server
    finally:
        server.remove()


@pytest.fixture(scope="session")
def postgres() -> Iterator[PostgresServer]:
    """One private PostgreSQL for the test session (`create_database()` per test)."""
    with running_postgres() as server:
        yield server
