"""Fixtures for the API tests: fast settings in the test's own directory, and a TestClient
of an app that racks every room with the 8-ball seed of `tests.support.games` (helpers for
rooms and sockets are in `tests.support`)."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from server.config import Settings
from tests.support.rooms import app_with
from tests.support.settings import settings_in


@pytest.fixture
def settings(tmp_path: Path) -> Settings:
    return settings_in(tmp_path)


@pytest.fixture
def client(settings: Settings) -> Iterator[TestClient]:
    with TestClient(app_with(settings)) as c:
        yield c
