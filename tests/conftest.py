"""Shared fixtures for the server tests: fast settings, an app, a TestClient, helpers."""

from __future__ import annotations

import os
import tempfile
import warnings

import pytest
from hypothesis import settings

from tests.support import tiers

# Property tests draw the same examples on every run (reproducible: a failure seen once is
# seen again), not a fresh random set each time.
settings.register_profile("reproducible", derandomize=True, database=None)
settings.load_profile("reproducible")

# Settings read from the environment open `POOL_DB_PATH` (default ./billiards.db): never
# the working tree. Tests that build `Settings(...)` give their own `db_path`.
os.environ["POOL_DB_PATH"] = os.path.join(tempfile.mkdtemp(prefix="billiards-"), "test.db")

# Starlette 1.10 asks for `httpx2` under its TestClient; plain httpx works the same here.
warnings.filterwarnings("ignore", message=".*httpx2.*")


@pytest.fixture(autouse=True)
def _own_database(tmp_path_factory, monkeypatch) -> None:
    """A fresh database per test, so rooms saved by one test are not restored in another."""
    monkeypatch.setenv("POOL_DB_PATH", str(tmp_path_factory.mktemp("db") / "billiards.db"))


@pytest.fixture(scope="session", autouse=True)
def _warm_engine() -> None:
    """Load (or, on a fresh clone, compile) the engine once before any test runs, so that
    no test that watches timing pays the one-off compile in the middle of a stream."""
    from server.engine import Shot, Table, rack, simulate

    table = Table.pool("9ft")
    simulate(table, rack("eight_ball", table), Shot(0.0, 9.0))


def pytest_configure(config: pytest.Config) -> None:
    for name, meaning in tiers.MARKERS.items():
        config.addinivalue_line("markers", f"{name}: {meaning}")


@pytest.hookimpl(wrapper=True)
def pytest_runtest_protocol(item: pytest.Item):
    """Tell the helpers which test is running, fixtures' set-up and teardown included."""
    tiers.entering(item)
    try:
        return (yield)
    finally:
        tiers.entering(None)
