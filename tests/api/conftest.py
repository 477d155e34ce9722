"""Fixtures for the API tests: fast settings in the test's own directory, and a TestClient
of an app that racks every room with the 8-ball seed of `tests.support.games` (helpers for
rooms and sockets are in `tests.support`), on the real clock or on a manual one."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from server.config import Settings
from server.rooms.clock import ManualClock
from tests.support.rooms import app_with
from tests.support.settings import settings_in


@pytest.fixture
def settings(tmp_path: Path) -> Settings:
    return settings_in(tmp_path)


@pytest.fixture
def client(settings: Settings) -> Iterator[TestClient]:
    with TestClient(app_with(settings)) as c:
        yield c


@pytest.fixture
def clock() -> ManualClock:
    return ManualClock()


@pytest.fixture
def clocked_client(settings: Settings, clock: ManualClock) -> Iterator[TestClient]:
    """`client`, but the app reads the time from `clock`: its waits (the Play now window
    widening, the computer offered after 20 s) pass when the test advances it, not by
    sleeping."""
    with TestClient(app_with(settings, clock=clock.clock)) as c:
        yield c
