"""A person plays the computer over the real WebSocket: the computer takes the second seat,
shows its cue moving, and plays its turns through the same room actions as a person."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from server.app import create_app
from server.rooms import SeedSource
from tests.support.games import BREAK_MESSAGE, EIGHT_BALL
from tests.support.settings import settings_in

pytestmark = pytest.mark.timeout(180)


@pytest.fixture
def client(tmp_path: Path) -> Iterator[TestClient]:
    settings = settings_in(tmp_path, computer_pause=0.0)
    with TestClient(create_app(settings, seeds=SeedSource.fixed(EIGHT_BALL))) as c:
        yield c


def test_the_computer_takes_the_second_seat_and_plays_its_turn(client: TestClient):
    created = client.post(
        "/api/rooms", json={"game": "eight_ball", "opponent": "club", "listed": False}
    )
    assert created.status_code == 201 and created.json()["opponent"] == "club"
    room_id = created.json()["room_id"]
    ana = client.post(f"/api/rooms/{room_id}/join", json={"name": "Ana"}).json()
    assert ana["seat"] == 0  # the person breaks
    room = client.get(f"/api/rooms/{room_id}").json()
    assert room["players"] == ["Ana", "Computer (club)"] and room["status"] == "playing"
    with client.websocket_connect(f"/ws/rooms/{room_id}?token={ana['token']}") as ws:
        while ws.receive_json()["type"] != "presence":
            pass
        ws.send_json(BREAK_MESSAGE)  # the rack's break: legal, then a miss hands over
        results = []
        aims = 0
        while len(results) < 3:
            message = ws.receive_json()
            aims += message["type"] == "aim" and message["seat"] == 1
            if message["type"] == "shot_result":
                results.append(message)
            if message["type"] != "state" or message["phase"] != "aiming" or not results:
                continue
            match = message["match"]
            if match["turn"] == 0 and match["decision"] is None:  # Ana's turn again
                if match["ball_in_hand"]:
                    ws.send_json({"type": "place_cue", "x": 0.5, "y": 0.6})
                ws.send_json({"type": "shoot", "angle": 2.0, "speed": 3.0})
    shooters = [r["outcome"]["shooter"] for r in results]
    assert 1 in shooters  # the computer shot
    assert aims >= 3  # and its cue was seen moving first


def test_the_computer_is_only_for_real_games_at_known_levels(client: TestClient):
    bad_level = client.post("/api/rooms", json={"game": "eight_ball", "opponent": "god"})
    practice = client.post("/api/rooms", json={"game": "practice", "opponent": "pro"})
    assert bad_level.status_code == 422 and practice.status_code == 422
