"""Bad HTTP input is refused with a 4xx, never a 500: bodies are strict (no coercion, as on
the socket), numbers finite, ids within the store's columns, names printable; the refusal
itself can always be written (it echoes the input)."""

from __future__ import annotations

import json
import logging
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
from fastapi.testclient import TestClient

from server.api.inputs import MAX_ROW_ID
from tests.support.rooms import app_with, create_room, join
from tests.support.settings import settings_in

pytestmark = pytest.mark.timeout(120)

JSON = {"content-type": "application/json"}
# Bodies for POST /api/rooms, as raw bytes: what a JSON library would not even write.
ROOM_BODIES = [
    b'{"game": "eight_ball", "shot_clock": NaN}',
    b'{"game": "eight_ball", "shot_clock": Infinity}',
    b'{"game": "eight_ball", "shot_clock": -Infinity}',
    b'{"game": "eight_ball", "shot_clock": 1e309}',
    b'{"game": "eight_ball", "shot_clock": "30"}',
    b'{"game": "eight_ball", "race_to": "3"}',
    b'{"game": "eight_ball", "race_to": 3.0}',
    b'{"game": "eight_ball", "race_to": true}',
    b'{"game": "eight_ball", "race_to": 1e400}',
    b'{"game": "eight_ball", "race_to": 1000000000000000000000000000000}',
    b'{"game": "eight_ball", "race_to": null}',
    b'{"game": "eight_ball", "listed": "yes"}',
    b'{"game": "eight_ball", "listed": 1}',
    b'{"game": "eight_ball", "ranked": "false"}',
    b'{"game": "eight_ball", "ranked": 0}',
    b'{"game": 5}',
    b'{"game": "\\ud800"}',
    b'{"game": "practice", "opponent": "\\udfff"}',
    b'{"game": "eight_ball", "opponent": 5}',
    b'{"game": "eight_ball", "extra": 1}',
    b'{"game": "eight_ball", "\\ud800": 1}',
    b"[]",
    b'"eight_ball"',
    b"42",
    b"null",
    b"",
    b"{",
    b'{"game": "eight_ball"',
    b"\xff\xfe\xfd",
    b'{"game": "\xff"}',
    b"[" * 5000 + b"]" * 5000,
    b'{"game": "eight_ball", "shot_clock": ' + b"9" * 5000 + b"}",
]
NAMES = [
    "\ud800",
    "a\ud800b",
    "\udfff",
    "\x00",
    "tab\there",
    "\x1b[31mred",
    "\u202eevil",  # right-to-left override: a format character, not printable
    "x" * 25,
    "",
]


def raw(value: Any) -> bytes:
    """`value` as JSON, lone surrogates escaped as JSON writes them."""
    return json.dumps(value).encode()


@pytest.fixture
def client(tmp_path: Path) -> Iterator[TestClient]:
    with TestClient(app_with(settings_in(tmp_path)), raise_server_exceptions=False) as c:
        yield c


def requests(client: TestClient) -> list[tuple[str, str, bytes | None]]:
    """The bad-input set: (method, path, body)."""
    practice = create_room(client, "practice")
    seat = join(client, practice, "Pia")
    rooms = [("POST", "/api/rooms", body) for body in ROOM_BODIES]
    names = [("POST", f"/api/rooms/{practice}/join", raw({"name": n})) for n in NAMES]
    names += [("PATCH", "/api/players/me", raw({"name": n})) for n in NAMES]
    joins = [
        ("POST", f"/api/rooms/{practice}/join", body)
        for body in (
            raw({"name": 5}),
            raw({"name": ["a"]}),
            raw({"name": "Ann", "ranked": "yes"}),
            b'{"name": "\\ud800\\udc00\\ud800"}',
        )
    ]
    hints = [
        ("POST", f"/api/rooms/{practice}/hint", body)
        for body in (raw({"token": 5}), raw({"token": "\ud800"}), raw({"token": ""}), b"{}")
    ]
    other = [
        ("POST", "/api/playnow", raw({"game": "\ud800"})),
        ("POST", "/api/playnow", raw({"game": 1})),
        ("POST", "/api/playnow", b'{"game": NaN}'),
    ]
    ids = [str(2**63), str(10**30), str(2**31), "-1", "abc", "1e3", "NaN"]
    gets = [("GET", f"/api/matches/{i}", None) for i in ids]
    gets += [("GET", f"/api/matches/1/shots/{i}/replay", None) for i in ids]
    gets += [("GET", f"/api/matches/{i}/shots/1/replay", None) for i in ids]
    gets += [
        ("GET", "/api/matches/1/shots/1/replay?pace=nan", None),
        ("GET", "/api/matches/1/shots/1/replay?pace=1e309", None),
        ("GET", "/api/matches?limit=1e999", None),
        ("GET", f"/api/matches?limit={2**63}", None),
        ("GET", "/api/matches?status=%ED%A0%80", None),
        ("GET", "/api/stats?window=nan", None),
        ("GET", "/api/stats?window=inf", None),
        ("GET", f"/api/rooms?offset={10**30}", None),
        ("GET", "/api/rooms/%ED%A0%80", None),
        ("GET", "/api/rooms/" + "x" * 5000, None),
        ("GET", "/api/players/%ED%A0%80", None),
        ("GET", "/api/leaderboard/%ED%A0%80", None),
    ]
    assert seat["seat"] == 0
    return rooms + names + joins + hints + other + gets


def test_no_bad_input_is_answered_500(client: TestClient, caplog: pytest.LogCaptureFixture):
    client.get("/api/players/me")  # a profile, for the rename
    caplog.set_level(logging.WARNING)
    statuses = []
    for method, path, body in requests(client):
        response = client.request(method, path, content=body, headers=JSON)
        statuses.append(response.status_code)
        assert 400 <= response.status_code < 500, (method, path, body, response.text)
        response.json()  # the refusal is JSON, whatever the input held
    assert 500 not in statuses
    tracebacks = [r for r in caplog.records if r.exc_info]
    assert tracebacks == []
    assert len(statuses) > 90


def test_bodies_are_not_coerced(client: TestClient):
    for field, value in [
        ("race_to", "3"),
        ("race_to", 3.0),
        ("race_to", True),
        ("listed", "yes"),
        ("ranked", "false"),
        ("shot_clock", "30"),
    ]:
        response = client.post("/api/rooms", json={"game": "eight_ball", field: value})
        assert response.status_code == 422, (field, value)
        assert response.json()["detail"][0]["loc"] == ["body", field]
    made = client.post(
        "/api/rooms", json={"game": "eight_ball", "race_to": 3, "shot_clock": 30, "listed": False}
    )
    assert made.status_code == 201, made.text  # an integer is a number of seconds
    assert (made.json()["race_to"], made.json()["shot_clock"]) == (3, 30.0)


def test_non_finite_numbers_are_refused_and_the_refusal_says_so(client: TestClient):
    for text in ("NaN", "Infinity", "1e309"):
        body = f'{{"game": "eight_ball", "shot_clock": {text}}}'.encode()
        response = client.post("/api/rooms", content=body, headers=JSON)
        assert response.status_code == 422
        (error,) = response.json()["detail"]
        assert error["type"] == "finite_number" and error["loc"] == ["body", "shot_clock"]


def test_names_are_refused_with_a_sentence(client: TestClient):
    room_id = create_room(client)
    for name, words in [("\ud800", "lone surrogate"), ("a\x00b", "printable")]:
        response = client.post(
            f"/api/rooms/{room_id}/join", content=raw({"name": name}), headers=JSON
        )
        assert response.status_code == 422
        detail = response.json()["detail"]
        assert detail["code"] == "bad_name" and words in detail["message"]
    assert client.get(f"/api/rooms/{room_id}").json()["players"] == [None, None]
    assert join(client, room_id, "Zoë 🎱")["name"] == "Zoë 🎱"  # any printable text is a name


def test_ids_beyond_the_store_are_refused_before_the_query(client: TestClient):
    for path in (f"/api/matches/{MAX_ROW_ID + 1}", f"/api/matches/1/shots/{2**63}/replay"):
        assert client.get(path).status_code == 422
    assert client.get(f"/api/matches/{MAX_ROW_ID}").status_code == 404
    assert client.get(f"/api/matches/1/shots/{MAX_ROW_ID}/replay").status_code == 404
