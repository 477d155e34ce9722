"""The standard solo drills through the API: a progressive line-up from `POST /api/drills`
(balls on the long string, a run until a miss, its best on the profile), and Rerack on a
ghost 9-ball or line-up table starting another try."""

from __future__ import annotations

import math

from fastapi.testclient import TestClient

from server.engine import Shot, Table
from tests.support.messages import greet, receive_until
from tests.support.rooms import connect, play_shot

TABLE = Table.pool("9ft")
MIDDLE = (TABLE.length / 2, TABLE.width / 2 + 0.3)  # above the line's middle ball
INTO_THE_SIDE = Shot(-math.pi / 2, 2.0)  # the middle ball straight into the side pocket
AWAY = Shot(math.pi / 2, 0.8)  # towards the other side rail, touching nothing


def open_drill(client: TestClient, kind: str) -> tuple[str, str]:
    """The drill's table with the visitor seated: (room id, token)."""
    created = client.post("/api/drills", json={"kind": kind})
    assert created.status_code == 201, created.text
    body = created.json()
    assert (body["kind"], body["game"], body["listed"], body["par"]) == (
        kind,
        "practice",
        False,
        None,
    )
    joined = client.post(f"/api/rooms/{body['room_id']}/join", json={"name": "Ana"})
    return body["room_id"], joined.json()["token"]


def test_a_lineup_run_scores_until_a_miss_and_its_best_goes_on_the_profile(client: TestClient):
    client.get("/api/players/me")  # the visitor's profile (its cookie kept by the client)
    room_id, token = open_drill(client, "lineup")
    state = client.get(f"/api/rooms/{room_id}").json()["state"]
    assert state["room"]["drill"] == {
        "kind": "lineup",
        "match": None,
        "n": None,
        "par": None,
        "made": None,
        "score": 0,
        "done": False,
        "won": False,
        "balls": 3,
        "tries": 1,
        "best": 0,
    }
    assert sorted(b[0] for b in state["balls"]) == [0, 1, 2, 3]
    assert state["match"]["ball_in_hand"] == "anywhere"
    with connect(client, room_id, token) as ws:
        _, state = greet(ws)
        _, seen, state = play_shot([ws], ws, state, INTO_THE_SIDE, MIDDLE)
        result = next(m for m in seen if m["type"] == "shot_result")
        assert result["outcome"]["pocketed"] == [2]
        drill = state["room"]["drill"]
        assert (drill["score"], drill["done"], drill["best"]) == (1, False, 1)
        assert state["match"]["ball_in_hand"] is None  # played from where it lies
        _, _, state = play_shot([ws], ws, state, AWAY)
        assert (state["room"]["drill"]["score"], state["room"]["drill"]["done"]) == (1, True)
        ws.send_json({"type": "rerack"})
        state = receive_until(ws, "state")[-1]
        drill = state["room"]["drill"]
        assert (drill["score"], drill["done"], drill["tries"], drill["best"]) == (0, False, 2, 1)
    drills = client.get("/api/players/me").json()["drills"]
    assert (drills["lineup_runs"], drills["lineup_best"]) == (1, 1)  # the second: not played


def test_rerack_on_a_ghost_table_starts_a_new_ghost_rack(client: TestClient):
    room_id, token = open_drill(client, "ghost")
    first = client.get(f"/api/rooms/{room_id}").json()["state"]["balls"]
    with connect(client, room_id, token) as ws:
        greet(ws)
        ws.send_json({"type": "rerack"})
        state = receive_until(ws, "state")[-1]
    assert sorted(b[0] for b in state["balls"]) == list(range(10))
    assert state["balls"] != first
    assert state["match"]["ball_in_hand"] == "behind_head_string"
    drill = state["room"]["drill"]
    assert (drill["kind"], drill["score"], drill["done"], drill["tries"]) == ("ghost", 0, False, 1)
