"""HTTP API: health, create, list, show, join, the third join refused, the web client."""

from __future__ import annotations

import re

import pytest
from fastapi.testclient import TestClient

from server.config import Settings
from server.rooms.clock import ManualClock
from tests.support.games import BREAK_MESSAGE
from tests.support.messages import greet, receive_until
from tests.support.rooms import (
    app_with,
    connect,
    create_room,
    join,
    make_client,
    seated_room,
)

pytestmark = pytest.mark.timeout(60)


def test_health(client):
    assert client.get("/health").json() == {"status": "ok"}


def test_create_room_returns_short_unguessable_id(client):
    response = client.post("/api/rooms", json={"game": "nine_ball", "race_to": 5, "shot_clock": 30})
    assert response.status_code == 201
    body = response.json()
    assert re.fullmatch(r"[A-Za-z0-9_-]{12}", body["room_id"])
    assert body | {"room_id": "x", "url": "x", "ws_url": "x"} == {
        "room_id": "x",
        "url": "x",
        "ws_url": "x",
        "game": "nine_ball",
        "race_to": 5,
        "shot_clock": 30.0,
        "seats": 2,
        "listed": True,
        "opponent": None,
        "ranked": False,
    }
    assert body["url"] == f"/r/{body['room_id']}"
    assert body["ws_url"] == f"ws://testserver/ws/rooms/{body['room_id']}"
    assert create_room(client) != create_room(client)


@pytest.mark.parametrize(
    "body",
    [
        {"game": "four_ball"},
        {"race_to": 3},
        {"game": "eight_ball", "race_to": 0},
        {"game": "eight_ball", "race_to": 16},
        {"game": "eight_ball", "race_to": "three"},
        {"game": "eight_ball", "shot_clock": -1},
        {"game": "eight_ball", "shot_clock": 601},
        {"game": "eight_ball", "colour": "red"},
    ],
)
def test_create_room_refuses_bad_bodies(client, body):
    assert client.post("/api/rooms", json=body).status_code == 422
    assert client.get("/api/rooms").json() == {"rooms": [], "total": 0, "next": None}


def test_shot_clock_below_minimum_is_refused(settings):
    with make_client(settings, min_shot_clock=5.0) as c:
        response = c.post("/api/rooms", json={"game": "eight_ball", "shot_clock": 2})
        assert response.status_code == 422
        assert response.json()["detail"]["code"] == "bad_shot_clock"
        assert c.post("/api/rooms", json={"game": "eight_ball", "shot_clock": 0}).status_code == 201


def test_shot_clock_above_the_maximum_is_refused(settings):
    """`POOL_MAX_SHOT_CLOCK` bounds the clock a new room may ask for."""
    bounded = Settings.from_env({"POOL_MAX_SHOT_CLOCK": "120"})
    with make_client(settings, max_shot_clock=bounded.max_shot_clock) as c:
        response = c.post("/api/rooms", json={"game": "eight_ball", "shot_clock": 121})
        assert response.status_code == 422
        assert response.json()["detail"] == {
            "code": "bad_shot_clock",
            "message": "The shot clock is at most 120 seconds.",
        }
        created = c.post("/api/rooms", json={"game": "eight_ball", "shot_clock": 120})
        assert created.status_code == 201 and created.json()["shot_clock"] == 120.0
        assert c.get("/api/rooms").json()["total"] == 1  # the refused one was not opened


def test_list_rooms_shows_game_status_players_and_spectators(settings):
    clock = ManualClock(now=1_767_000_000.0)
    with TestClient(app_with(settings, clock=clock.clock)) as client:
        waiting = create_room(client, "eight_ball", race_to=3)
        join(client, waiting, "Ana")
        clock.advance(1.5)
        practice = create_room(client, "practice")
        join(client, practice, "Pia")
        clock.advance(1.5)
        full = create_room(client, "nine_ball")
        join(client, full, "Ana")
        join(client, full, "Ben")
        with client.websocket_connect(f"/ws/rooms/{full}") as spectator:
            spectator.receive_json()
            listing = client.get("/api/rooms").json()["rooms"]
    assert [r["room_id"] for r in listing] == [full, practice, waiting]  # newest first
    rooms = {r["room_id"]: r for r in listing}
    assert rooms[waiting]["status"] == "waiting"
    assert rooms[waiting]["players"] == ["Ana", None]
    assert rooms[waiting]["race_to"] == 3
    assert rooms[waiting]["score"] is None
    assert rooms[practice] == {
        "room_id": practice,
        "game": "practice",
        "race_to": 1,
        "shot_clock": 0.0,
        "seats": 1,
        "status": "playing",
        "players": ["Pia"],
        "spectators": 0,
        "score": [0],
        "created_at": 1_767_000_001.5,
        "ranked": False,
    }
    assert rooms[full]["status"] == "playing"
    assert rooms[full]["players"] == ["Ana", "Ben"]
    assert rooms[full]["spectators"] == 1
    assert rooms[full]["score"] == [0, 0]
    assert [r["created_at"] for r in listing] == [1_767_000_003.0, 1_767_000_001.5, 1_767_000_000.0]


def test_show_room_and_unknown_room(client):
    room_id = create_room(client)
    body = client.get(f"/api/rooms/{room_id}").json()
    assert body["status"] == "waiting"
    assert body["state"]["phase"] == "waiting"
    assert body["state"]["match"] is None
    assert body["state"]["table"]["length"] == pytest.approx(2.54)
    join(client, room_id, "Ana")
    join(client, room_id, "Ben")
    state = client.get(f"/api/rooms/{room_id}").json()["state"]
    assert state["phase"] == "aiming"
    assert state["match"]["turn"] == 0
    assert len(state["balls"]) == 16
    assert all(len(row) == 4 and all(isinstance(v, int) for v in row) for row in state["balls"])
    missing = client.get("/api/rooms/nosuchroom00")
    assert missing.status_code == 404
    assert missing.json()["detail"]["code"] == "unknown_room"
    assert client.post("/api/rooms/nosuchroom00/join", json={"name": "A"}).status_code == 404


def test_an_unknown_room_is_refused_after_the_body_and_the_quota(settings):
    """Every route about one room answers 404 `unknown_room` the same way, and only once
    its body is valid (422 first) and the client is within its quota (429 first)."""
    with make_client(settings, join_rate="1/minute") as client:
        hint = client.post("/api/rooms/nosuchroom00/hint", json={"token": "t"})
        assert hint.status_code == 404
        assert hint.json() == {"detail": {"code": "unknown_room", "message": "No such room."}}
        assert client.post("/api/rooms/nosuchroom00/hint", json={}).status_code == 422
        assert client.post("/api/rooms/nosuchroom00/join", json={"name": ""}).status_code == 422
        joined = client.post("/api/rooms/nosuchroom00/join", json={"name": "A"})
        assert joined.status_code == 404
        assert joined.json() == hint.json()
        again = client.post("/api/rooms/nosuchroom00/join", json={"name": "A"})
        assert again.status_code == 429
        assert again.json()["detail"]["code"] == "rate_limited"


def test_join_gives_seats_then_refuses_the_third(client):
    room_id = create_room(client)
    a = join(client, room_id, "  Ana  ")
    b = join(client, room_id, "Ben")
    assert (a["seat"], a["name"], b["seat"]) == (0, "Ana", 1)
    assert a["token"] != b["token"] and len(a["token"]) >= 40
    third = client.post(f"/api/rooms/{room_id}/join", json={"name": "Cy"})
    assert third.status_code == 409
    assert third.json()["detail"]["code"] == "room_full"
    assert client.get(f"/api/rooms/{room_id}").json()["players"] == ["Ana", "Ben"]


def test_practice_has_one_seat(client):
    room_id = create_room(client, "practice")
    assert join(client, room_id, "Pia")["seat"] == 0
    assert client.post(f"/api/rooms/{room_id}/join", json={"name": "X"}).status_code == 409


@pytest.mark.parametrize("name", ["", "   ", "x" * 25, "tab\there", "new\nline", "\x00"])
def test_join_refuses_bad_names(client, name):
    room_id = create_room(client)
    response = client.post(f"/api/rooms/{room_id}/join", json={"name": name})
    assert response.status_code == 422
    assert client.get(f"/api/rooms/{room_id}").json()["players"] == [None, None]


def test_tokens_are_stored_only_as_hashes(client):
    room_id = create_room(client)
    token = join(client, room_id, "Ana")["token"]
    room = client.app.state.registry.get(room_id).room
    assert token not in repr(vars(room)) and token not in repr(room.seats)


def test_openapi_documents_the_endpoints(client):
    paths = client.get("/openapi.json").json()["paths"]
    assert {"/health", "/api/rooms", "/api/rooms/{room_id}", "/api/rooms/{room_id}/join"} <= set(
        paths
    )


def test_web_client_is_served_at_root_and_room_links(client):
    index = client.get("/")
    assert index.status_code == 200 and "lobby" in index.text
    assert client.get("/js/app.js").text.startswith("export")
    room_id = create_room(client)
    link = client.get(f"/r/{room_id}")
    assert link.status_code == 200 and link.text == index.text
    assert link.headers["content-type"].startswith("text/html")
    replay = client.get("/m/5")  # a finished match's replay: the client routes on the path
    assert replay.status_code == 200 and replay.text == index.text


def test_stats_report_rooms_connections_and_frame_lateness(settings):
    with make_client(settings, pace=4.0) as client:
        empty = client.get("/api/stats").json()
        assert empty["rooms"] == 0 and empty["stream"]["frames"] == 0
        assert empty["stream"]["late_p99_ms"] is None
        assert empty["stream"]["shots"] == 0 and empty["stream"]["start_p50_ms"] is None
        room_id, ta, _ = seated_room(client)
        with connect(client, room_id, ta) as a:
            greet(a)
            a.send_json(BREAK_MESSAGE)
            motions = [m for m in receive_until(a, "state") if m["type"] == "motion"]
            stats = client.get("/api/stats", params={"window": 60}).json()
        assert stats["rooms"] == 1 and stats["connections"] == 1
        stream = stats["stream"]
        # One `motion` message a shot, the whole shot in it.
        assert stream["frames"] == stream["frames_sent"] == len(motions) == 1
        assert 0 <= stream["late_p50_ms"] <= stream["late_p99_ms"] <= stream["late_max_ms"]
        assert stream["shots"] == 1 and 0 < stream["start_p50_ms"] == stream["start_p99_ms"]
        assert client.get("/api/stats", params={"window": 0}).status_code == 422
        assert client.get("/api/stats", params={"window": "nan"}).status_code == 422
