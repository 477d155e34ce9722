"""A replay shows what was played, whatever engine the server runs now: each shot is stored
with the engine version that played it and the motion every member was shown."""

from __future__ import annotations

import base64
import json
import zlib

import pytest
from fastapi.testclient import TestClient

from server.engine import ENGINE_VERSION
from server.protocol.motion import decode_motion
from tests.support.games import BREAK_MESSAGE
from tests.support.messages import assert_valid, greet, receive_until, shot_payload
from tests.support.rooms import connect, seated_room

pytestmark = pytest.mark.timeout(120)


def live_break(client: TestClient) -> dict:
    """A break in a new 8-ball room: the `motion` message its spectator got (decoded)."""
    room_id, token, _ = seated_room(client)
    with connect(client, room_id) as watcher, connect(client, room_id, token) as ana:
        greet(watcher)
        greet(ana)
        ana.send_json(BREAK_MESSAGE)
        stream = receive_until(watcher, "shot_result")
    (motion,) = [m for m in stream if m["type"] == "motion"]
    return motion


def assert_replays(lines: list[dict], live: dict) -> None:
    """The replay (`lines`: the `motion` line, then `shot_result`) carries the very motion
    shown live (the bytes in base64; only the sequence number is the replay's own)."""
    assert [m["type"] for m in lines] == ["motion", "shot_result"]
    assert_valid(lines, replay=True)
    replayed = decode_motion(base64.b64decode(lines[0]["data"]))
    assert replayed["seq"] == lines[0]["seq"] == 1
    assert shot_payload(replayed) == shot_payload(live)
    assert lines[0]["shot"] == live["shot"]


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
    )  # the current engine could not reproduce it
    status, lines = replay(client)
    assert status == 200
    assert_replays(lines, live)


def test_a_row_without_motion_is_simulated_again_only_by_its_own_engine(client):
    live = live_break(client)
    set_row(client, "UPDATE shots SET motion = NULL")  # engine: the current one
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


# What a room stored for a shot before the `motion` message: its `frame` and `event`
# messages, one a line (`at kind body`), shortened to three frames of two balls.
LEGACY = (
    '0.0 event {"shot":1,"tick":0,"t":0.0,"kind":"strike","ids":[0],"speed":9.0,"target":-1,'
    '"also":[{"tick":17,"t":0.1367,"kind":"ball","ids":[0,9],"speed":8.732,"target":-1}]}\n'
    '0.05 frame {"shot":1,"tick":6,"b":[[0,1083,635,0],[9,2103,635,0]],'
    '"ahead":[{"tick":12,"b":[[0,1526,635,2],[9,2103,635,0]]}]}\n'
    '0.15 frame {"shot":1,"tick":18,"b":[[0,1836,635,3]],"last":true}\n'
    '0.1 event {"shot":1,"tick":12,"t":0.1,"kind":"pocket","ids":[9],"speed":2.0,"target":2}\n'
)


def test_a_shot_stored_as_frames_and_events_still_replays(client):
    live_break(client)
    set_row(client, "UPDATE shots SET motion = ?", zlib.compress(LEGACY.encode()))
    status, lines = replay(client)
    assert status == 200 and [m["type"] for m in lines] == ["motion", "shot_result"]
    motion = decode_motion(base64.b64decode(lines[0]["data"]))
    assert motion["duration"] == pytest.approx(18 / 120, abs=1e-6)
    cue, nine = motion["tracks"]
    assert cue["t"] == pytest.approx([0.05, 0.1, 0.15])  # the frames' ticks are its knots
    assert cue["x"] == pytest.approx([1.083, 1.526, 1.836])
    assert nine["pocket"] == 2 and nine["t"] == pytest.approx([0.05, 0.1])
    # cels 0 -> 2 over 443 mm: 2.47 turns rolled, the step nearest to it (2 cels + 2 turns)
    assert nine["phase"][1] == nine["phase"][0]
    assert cue["phase"][1] - cue["phase"][0] == pytest.approx(
        (2 + 2 * 16) * 2 * 3.14159265 / 16, abs=1e-3
    )
    assert [(e["kind"], e["t"]) for e in motion["sounds"]] == [
        ("strike", 0.0),
        ("pocket", 0.1),
        ("ball", 0.1367),
    ]
