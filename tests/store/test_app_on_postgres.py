"""`POOL_DATABASE_URL` puts the server's rooms and history in PostgreSQL: a room created and
joined through the API survives a restart from there, and no SQLite file is made."""

from __future__ import annotations

from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from server.app import create_app
from server.config import Settings, SettingsError
from tests.support.postgres import PostgresServer
from tests.support.settings import settings_in


@pytest.mark.postgres
def test_a_server_on_postgresql_keeps_its_rooms_there_across_a_restart(
    postgres: PostgresServer, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    url = postgres.create_database()
    settings = settings_in(tmp_path)
    monkeypatch.setenv("POOL_DATABASE_URL", url)
    monkeypatch.setenv("POOL_DB_PATH", str(settings.db_path))
    monkeypatch.setenv("POOL_WEB_DIR", str(settings.web_dir))
    with TestClient(create_app()) as client:  # settings from the environment
        assert client.app.state.store.backend == "postgresql"  # type: ignore[attr-defined]
        room_id = client.post("/api/rooms", json={"game": "nine_ball"}).json()["room_id"]
        client.post(f"/api/rooms/{room_id}/join", json={"name": "Ana"})
    with TestClient(create_app()) as client:
        room = client.get(f"/api/rooms/{room_id}").json()
        rooms = client.app.state.store.run(lambda r: r.rooms())  # type: ignore[attr-defined]
    assert (room["game"], room["players"]) == ("nine_ball", ["Ana", None])
    assert [r.room_id for r in rooms] == [room_id]
    assert not settings.db_path.exists()


def test_a_database_url_that_is_not_postgresql_stops_the_server_with_its_name() -> None:
    with pytest.raises(SettingsError, match="POOL_DATABASE_URL"):
        Settings.from_env({"POOL_DATABASE_URL": "mysql://pool@db/pool"})
    settings = Settings.from_env({"POOL_DATABASE_URL": "postgresql://pool@db:5432/pool"})
    assert settings.database == "postgresql://pool@db:5432/pool"
    assert Settings.from_env({"POOL_DB_PATH": "x.db"}).database == Path("x.db")
