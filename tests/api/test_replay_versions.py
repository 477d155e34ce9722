"""A replay shows what was played, whatever engine the server runs now: each shot is stored
with the engine version that played it and the motion every member was shown."""

from __future__ import annotations

import json

import pytest
from fastapi.testclient import TestClient

from server.app import create_app
from server.engine import ENGINE_VERSION
from server.rooms import SeedSource

pytestmark = pytest.mark.timeout(120)
BREAK = {"type": "shoot", "angle": 0.0, "speed": 9.0}


def without_seq(message: dict) -> dict:
    return {k: v for k, v in message.items() if k != "seq"}


def live_break(client: TestClient) -> list[dict]:
    """A break in a new 8-ball room, as its spectator saw it: frames and events."""
    room_id = client.post("/api/rooms", json={"game": "eight_ball"}).json()["room_id"]
    token = client.post(f"/api/rooms/{room_id}/join", json={"name": "Ana"}).json()["token"]
    client.post(f"/api/rooms/{room_id}/join", json={"name": "Ben"})
    seen = []
    with client.websocket_connect(f"/ws/rooms/{room_id}") as watcher, \
            client.websocket_connect(f"/ws/rooms/{room_id}?token={token}") as ana:
        while (message := ana.receive_json())["type"] != "presence":
            pass
        ana.send_json(BREAK)
        while (message := watcher.receive_json())["type"] != "shot_result":
            if message["type"] in ("frame", "event"):
                seen.append(without_seq(message))
    return seen


def replay(client: TestClient, match_id: int = 1, n: int = 1) -> tuple[int, list[dict]]:
    response = client.get(f"/api/matches/{match_id}/shots/{n}/replay?pace=100")
    if response.status_code != 200:
        return response.status_code, [response.json()]
    return 200, [json.loads(line) for line in response.text.splitlines()]


def set_row(client: TestClient, sql: str, *params: object) -> None:
    store = client.app.state.store  # type: ignore[attr-defined]
    store.run(lambda repo: repo.conn.execute(sql, params))


@pytest.fixture
def client(tmp_path) -> TestClient:
    from server.config import Settings

    settings = Settings(pace=20.0, web_dir=tmp_path, db_path=tmp_path / "pool.db")
    with TestClient(create_app(settings, seeds=SeedSource.fixed(11))) as c:
        yield c


def test_a_shot_is_stored_with_its_engine_and_replays_exactly_what_was_shown(client):
    live = live_break(client)
    detail = client.get("/api/matches/1").json()
    assert [s["engine"] for s in detail["shots"]] == [ENGINE_VERSION]
    assert detail["stream"] == {"tick_hz": 120, "frame_every": 6, "frames_per_message": 4}
    status, lines = replay(client)
    assert status == 200
    assert [without_seq(m) for m in lines[:-1]] == live
    assert [m["seq"] for m in lines] == list(range(1, len(lines) + 1))
    assert lines[-1]["type"] == "shot_result" and lines[-1]["replay"] == {"match": 1, "n": 1}


def test_a_shot_played_by_another_engine_replays_its_stored_motion(client):
    live = live_break(client)
    set_row(client, "UPDATE shots SET engine = '0+older', table_geom = '[2.0,1.0,0.03,0.1,"
            "0.1]' WHERE match_id = 1 AND n = 1")  # today's engine could not reproduce it
    status, lines = replay(client)
    assert status == 200 and [without_seq(m) for m in lines[:-1]] == live


def test_an_old_row_without_motion_is_simulated_again_only_by_its_own_engine(client):
    # Rows from before versions were recorded belong to FIRST_RECORDED_ENGINE: when the
    # physics changes, this test fails and the first replay below must become a 409.
    live = live_break(client)
    set_row(client, "UPDATE shots SET motion = NULL, engine = NULL")  # stored before versions
    status, lines = replay(client)
    assert status == 200 and [without_seq(m) for m in lines[:-1]] == live

    set_row(client, "UPDATE shots SET engine = '0+older'")
    status, body = replay(client)
    assert status == 409 and body[0]["detail"]["code"] == "engine_changed"

