"""Fixtures for the API tests: an app with fast clocks, a TestClient, room helpers."""

from __future__ import annotations

import json
from collections.abc import Iterator
from pathlib import Path

import pytest
from fastapi.testclient import TestClient
from starlette.testclient import WebSocketTestSession

from server.app import create_app
from server.config import Settings

FAST = Settings(pace=20.0, grace=60.0, min_shot_clock=0.1, send_timeout=0.5, shot_workers=0)
BREAK = {"type": "shoot", "angle": 0.0, "speed": 9.0, "tip": [0.0, 0.0]}


@pytest.fixture
def settings(tmp_path: Path) -> Settings:
    web = tmp_path / "web"
    web.mkdir()
    (web / "index.html").write_text("<!doctype html><title>pool</title><p>lobby</p>")
    (web / "app.js").write_text("export const ok = true;\n")
    return FAST.replace(web_dir=web, db_path=tmp_path / "billiards.db")


@pytest.fixture
def client(settings: Settings) -> Iterator[TestClient]:
    with TestClient(create_app(settings)) as c:
        yield c


def make_client(settings: Settings, **changes) -> TestClient:
    return TestClient(create_app(settings.replace(**changes)))


def create_room(client: TestClient, game: str = "eight_ball", **extra) -> str:
    response = client.post("/api/rooms", json={"game": game, **extra})
    assert response.status_code == 201, response.text
    return response.json()["room_id"]


def join(client: TestClient, room_id: str, name: str) -> dict:
    response = client.post(f"/api/rooms/{room_id}/join", json={"name": name})
    assert response.status_code == 200, response.text
    return response.json()


def seated_room(client: TestClient, game: str = "eight_ball", **extra) -> tuple[str, str, str]:
    """A room with both seats taken: (room_id, token of seat 0, token of seat 1)."""
    room_id = create_room(client, game, **extra)
    a = join(client, room_id, "Ana")
    b = join(client, room_id, "Ben")
    assert (a["seat"], b["seat"]) == (0, 1)
    return room_id, a["token"], b["token"]


def connect(client: TestClient, room_id: str, token: str | None = None,
            **kwargs) -> WebSocketTestSession:
    url = f"/ws/rooms/{room_id}" + (f"?token={token}" if token else "")
    return client.websocket_connect(url, **kwargs)


def greet(ws: WebSocketTestSession) -> tuple[dict, dict]:
    """Read the `welcome`, `state` and own `presence` every new connection gets first."""
    welcome = ws.receive_json()
    assert welcome["type"] == "welcome"
    state = ws.receive_json()
    assert state["type"] == "state" and state["seq"] == welcome["seq"]
    presence = ws.receive_json()
    assert presence["type"] == "presence" and presence["seq"] == welcome["seq"] + 1
    return welcome, state


def receive_until(ws: WebSocketTestSession, kind: str, limit: int = 5000) -> list[dict]:
    """Messages up to and including the first of type `kind`."""
    out = []
    for _ in range(limit):
        message = ws.receive_json()
        out.append(message)
        if message["type"] == kind:
            return out
    raise AssertionError(f"no {kind} within {limit} messages")


def roundtrip(ws: WebSocketTestSession, payload: dict | str) -> list[dict]:
    """Send, then a ping; returns what came back before the pong (proves the socket lives)."""
    ws.send_text(payload if isinstance(payload, str) else json.dumps(payload))
    ws.send_text('{"type": "ping", "id": 99}')
    got = receive_until(ws, "pong")
    assert got[-1]["id"] == 99
    return got[:-1]


def errors_in(messages: list[dict]) -> list[dict]:
    return [m for m in messages if m["type"] == "error"]


def flat_events(stream: list[dict]) -> list[dict]:
    """Every event of a stream in time order: each `event` message and the events it
    carries in `also` (with the message's shot)."""
    out = []
    for m in stream:
        if m["type"] == "event":
            out.append(m)
            out.extend({"type": "event", "shot": m["shot"], **a} for a in m.get("also", ()))
    return out


def flat_frames(stream: list[dict]) -> list[dict]:
    """Every frame of a stream in tick order: each `frame` message and the frames it
    carries early in `ahead` (with the message's shot)."""
    out = []
    for m in stream:
        if m["type"] == "frame":
            out.append(m)
            out.extend({"type": "frame", "shot": m["shot"], **a} for a in m.get("ahead", ()))
    return out
