"""Fixtures for the accounts' tests: the app of `tests/api`, on a manual clock (sessions
expire when the test says), with its own store."""

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
def clock() -> ManualClock:
    return ManualClock()


@pytest.fixture
def client(settings: Settings, clock: ManualClock) -> Iterator[TestClient]:
    with TestClient(app_with(settings, clock=clock.clock)) as c:
        yield c
