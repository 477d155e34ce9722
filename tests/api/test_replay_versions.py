"""A replay shows what was played, whatever engine the server runs now: each shot is stored
with the engine version that played it and the motion every member was shown."""

from __future__ import annotations

import json

import pytest
from fastapi.testclient import TestClient

from server.engine import ENGINE_VERSION
from tests.support.games import BREAK_MESSAGE
from tests.support.messages import greet, is_subsequence, of_type, receive_until, shot_payload
from tests.support.rooms import connect, seated_room

pytestmark = pytest.mark.timeout(120)


def live_break(client: TestClient) -> list[dict]:
    """A break in a new 8-ball room, as its spectator saw it: frames and events."""
    room_id, token, _ = seated_room(client)
    with connect(client, room_id) as watcher, connect(client, room_id, token) as ana:
        greet(watcher)
        greet(ana)
        ana.send_json(BREAK_MESSAGE)
        stream = receive_until(watcher, "shot_result")
    return [shot_payload(m) for m in stream if m["type"] in ("frame", "event")]


def assert_replays(lines: list[dict], live: list[dict]) -> None:
    """The replay (`lines`, its `shot_result` last) is the stream the room planned: every
    event and the last frame as shown live, and every frame shown live, in order (a room
    running late skips stale frames live; the replay never does)."""
    replayed = [shot_payload(m) for m in lines[:-1]]
    assert is_subsequence(live, replayed)
    assert of_type(replayed, "event") == of_type(live, "event")
    assert replayed[-1] == live[-1] and live[-1]["last"]
    frames = of_type(replayed, "frame")
    assert [f["tick"] for f in frames] == sorted({f["tick"] for f in frames})


def replay(client: TestClient, match_id: int = 1, n: int = 1) -> tuple[int, list[dict]]:
    response = client.get(f"/api/matches/{match_id}/shots/{n}/replay?pace=100")
    if response.status_code != 200:
        return response.status_code, [response.json()]
    return 200, [json.loads(line) for line in response.text.splitlines()]


def set_row(client: TestClient, sql: str, *params: object) -> None:
    store = client.app.state.store  # type: ignore[attr-defined]
    store.run(lambda repo: repo.conn.execute(sql, params))


def test_a_shot_is_stored_with_its_engine_and_replays_exactly_what_was_shown(client):
    live = live_break(client)
    detail = client.get("/api/matches/1").json()
    assert [s["engine"] for s in detail["shots"]] == [ENGINE_VERSION]
    assert detail["stream"] == {"tick_hz": 120, "frame_every": 6, "frames_per_message": 4}
    status, lines = replay(client)
    assert status == 200
    assert_replays(lines, live)
    assert [m["seq"] for m in lines] == list(range(1, len(lines) + 1))
    assert lines[-1]["type"] == "shot_result" and lines[-1]["replay"] == {"match": 1, "n": 1}


def test_a_shot_played_by_another_engine_replays_its_stored_motion(client):
    live = live_break(client)
    set_row(
        client,
        "UPDATE shots SET engine = '0+older', table_geom = '[2.0,1.0,0.03,0.1,"
        "0.1]' WHERE match_id = 1 AND n = 1",
    )  # today's engine could not reproduce it
    status, lines = replay(client)
    assert status == 200
    assert_replays(lines, live)


def test_a_row_without_motion_is_simulated_again_only_by_its_own_engine(client):
    live = live_break(client)
    set_row(client, "UPDATE shots SET motion = NULL")  # engine: today's
    status, lines = replay(client)
    assert status == 200
    assert_replays(lines, live)

    set_row(client, "UPDATE shots SET engine = '0+older'")
    status, body = replay(client)
    assert status == 409 and body[0]["detail"]["code"] == "engine_changed"


def test_rows_from_before_engine_versions_belong_to_the_first_recorded_engine(client):
    from server.rooms.replay import FIRST_RECORDED_ENGINE

    live_break(client)
    set_row(client, "UPDATE shots SET motion = NULL, engine = NULL")  # stored before versions
    status, body = replay(client)
    # The physics changed since: a re-simulation would show another shot than was played.
    assert FIRST_RECORDED_ENGINE != ENGINE_VERSION
    assert status == 409 and body[0]["detail"]["code"] == "engine_changed"
