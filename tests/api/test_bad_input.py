"""Bad input changes nothing and keeps the socket open; size and floods close it."""

from __future__ import annotations

import json

import pytest
from starlette.websockets import WebSocketDisconnect

from tests.support.messages import errors_in, greet, roundtrip
from tests.support.rooms import connect, create_room, join, make_client, seated_room

pytestmark = pytest.mark.timeout(60)

SHOOT = {"type": "shoot", "angle": 0.0, "speed": 5.0}

BAD = [
    ("not json", "bad_json"),
    ('{"type": "shoot", ', "bad_json"),
    ("[1, 2, 3]", "bad_json"),
    ("42", "bad_json"),
    ('"shoot"', "bad_json"),
    ("{}", "unknown_type"),
    ('{"type": "teleport", "ball": 8}', "unknown_type"),
    ('{"type": 5}', "unknown_type"),
    ('{"type": "shoot", "speed": 5.0}', "bad_message"),
    ('{"type": "shoot", "angle": "left", "speed": 5.0}', "bad_message"),
    ('{"type": "shoot", "angle": 0.0, "speed": NaN}', "bad_message"),
    ('{"type": "shoot", "angle": Infinity, "speed": 5.0}', "bad_message"),
    ('{"type": "shoot", "angle": 0.0, "speed": -Infinity}', "bad_message"),
    ('{"type": "shoot", "angle": 0.0, "speed": 1e400}', "bad_message"),
    ('{"type": "shoot", "angle": 0.0, "speed": 0}', "bad_message"),
    ('{"type": "shoot", "angle": 0.0, "speed": 12.5}', "bad_message"),
    ('{"type": "shoot", "angle": 0.0, "speed": -3}', "bad_message"),
    ('{"type": "shoot", "angle": 1e9, "speed": 3}', "bad_message"),
    ('{"type": "shoot", "angle": 0.0, "speed": 5.0, "tip": [0.6, 0.0]}', "bad_message"),
    ('{"type": "shoot", "angle": 0.0, "speed": 5.0, "tip": [0.4, 0.4]}', "bad_message"),
    ('{"type": "shoot", "angle": 0.0, "speed": 5.0, "tip": [0.1]}', "bad_message"),
    ('{"type": "shoot", "angle": 0.0, "speed": 5.0, "tip": "top"}', "bad_message"),
    ('{"type": "shoot", "angle": 0.0, "speed": 5.0, "power": 1}', "bad_message"),
    ('{"type": "place_cue", "x": 0.4}', "bad_message"),
    ('{"type": "place_cue", "x": NaN, "y": 0.5}', "bad_message"),
    ('{"type": "aim", "angle": 0.0, "power": 2}', "bad_message"),
    ('{"type": "call", "pocket": 6}', "bad_message"),
    ('{"type": "call", "pocket": 1.5}', "bad_message"),
    ('{"type": "chat", "text": ""}', "bad_message"),
    (json.dumps({"type": "chat", "text": "x" * 201}), "bad_message"),
    ('{"type": "ping", "id": -1}', "bad_message"),
]


def test_every_bad_message_gets_an_error_and_changes_nothing(settings):
    with (
        make_client(settings, rate_burst=1000) as client,
        connect(client, *seated_room(client)[:2]) as a,
    ):
        greet(a)
        before = roundtrip(a, {"type": "sync"})[-1]
        for text, code in BAD:
            got = roundtrip(a, text)
            errors = errors_in(got)
            assert [e["code"] for e in errors] == [code], text
            assert errors[0]["message"]
            assert [m for m in got if m["type"] != "error"] == []  # nothing was broadcast
        a.send_bytes(b'{"type": "ping"}')
        assert errors_in(roundtrip(a, {"type": "sync"}))[0]["code"] == "binary_not_supported"
        after = roundtrip(a, {"type": "sync"})[-1]
        assert after["seq"] == before["seq"]  # no broadcast happened
        assert after["balls"] == before["balls"] and after["match"] == before["match"]
        assert errors_in(roundtrip(a, SHOOT)) == []  # still the shooter: the shot is taken


def test_ball_in_hand_on_another_ball_is_refused(client):
    room_id = create_room(client, "practice")
    token = join(client, room_id, "Pia")["token"]
    with connect(client, room_id, token) as p:
        _, state = greet(p)
        one = next(row for row in state["balls"] if row[0] == 1)
        for x, y in [
            (one[1] / 1000, one[2] / 1000),
            (one[1] / 1000 + 0.01, one[2] / 1000),
            (-0.5, 0.5),
            (3.0, 0.5),
        ]:
            errors = errors_in(roundtrip(p, {"type": "place_cue", "x": x, "y": y}))
            assert [e["code"] for e in errors] == ["illegal_placement"]
        assert roundtrip(p, {"type": "sync"})[-1]["balls"] == state["balls"]


def test_wrong_token_and_unknown_room_are_refused_before_accept(client):
    room_id, ta, _ = seated_room(client)
    for url in (
        f"/ws/rooms/{room_id}?token=not-a-token",
        f"/ws/rooms/{room_id}?token=",
        f"/ws/rooms/{room_id}?token={ta}x",
        f"/ws/rooms/nosuchroom00?token={ta}",
        "/ws/rooms/nosuchroom00",
    ):
        with pytest.raises(WebSocketDisconnect) as refused, client.websocket_connect(url):
            pass
        assert refused.value.code == 1008, url
    assert client.get(f"/api/rooms/{room_id}").json()["spectators"] == 0


def test_message_over_16_kib_closes_with_1009(client):
    room_id, ta, _ = seated_room(client)
    with connect(client, room_id, ta) as a:
        greet(a)
        roundtrip(a, {"type": "chat", "text": "x" * 200})  # big but legal
        a.send_text(json.dumps({"type": "chat", "text": "y" * (17 * 1024)}))
        with pytest.raises(WebSocketDisconnect) as closed:
            for _ in range(50):
                a.receive_json()
        assert closed.value.code == 1009


def test_flood_closes_with_1008(settings):
    with make_client(settings, rate_burst=10, rate_per_second=5) as client:
        room_id, ta, _ = seated_room(client)
        with connect(client, room_id, ta) as a:
            greet(a)
            roundtrip(a, {"type": "sync"})  # a normal pace is fine
            for i in range(30):
                a.send_text(json.dumps({"type": "ping", "id": i}))
            pongs = 0
            with pytest.raises(WebSocketDisconnect) as closed:
                for _ in range(100):
                    pongs += a.receive_json()["type"] == "pong"
            assert closed.value.code == 1008
            assert pongs < 30


def test_foreign_origin_is_refused(client):
    room_id, ta, _ = seated_room(client)
    for origin in ("http://evil.example", "null", "https://testserver.evil.example"):
        with (
            pytest.raises(WebSocketDisconnect) as refused,
            connect(client, room_id, ta, headers={"origin": origin}),
        ):
            pass
        assert refused.value.code == 1008
    with connect(client, room_id, ta, headers={"origin": "http://testserver"}) as a:
        assert greet(a)[0]["seat"] == 0


def test_allow_listed_origin_is_accepted(settings):
    with make_client(settings, allowed_origins=("https://pool.example",)) as client:
        room_id = create_room(client)
        with connect(client, room_id, headers={"origin": "https://pool.example"}) as s:
            assert greet(s)[0]["role"] == "spectator"
        with (
            pytest.raises(WebSocketDisconnect),
            connect(client, room_id, headers={"origin": "https://other.example"}),
        ):
            pass
