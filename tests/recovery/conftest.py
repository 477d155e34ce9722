"""Fixtures for the storage and recovery tests: fast settings with the test's own database
(helpers for real servers, rooms and sockets are in `tests.support`)."""

from __future__ import annotations

from pathlib import Path

import pytest

from server.config import Settings
from tests.support.settings import settings_in


@pytest.fixture
def settings(tmp_path: Path) -> Settings:
    """Real servers on a busy machine: a client may take up to 2 s to read."""
    return settings_in(tmp_path, send_timeout=2.0)
