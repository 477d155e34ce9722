"""Apps that deal fixed racks, and rooms over HTTP: create, join, seat two players, play.

The HTTP helpers take any `httpx.Client`: a TestClient, or `live.http(address)` on a real
server.
"""

from __future__ import annotations

import functools
from collections.abc import Sequence
from typing import Any

import httpx
from fastapi import FastAPI
from fastapi.testclient import TestClient
from starlette.testclient import WebSocketTestSession

from server.app import create_app
from server.config import Settings
from server.engine import Shot
from server.rooms import SYSTEM_CLOCK, Clock, SeedSource
from server.store import Database

from .games import EIGHT_BALL, shoot_message
from .messages import Socket, receive_any, receive_until


def app_with(
    settings: Settings,
    seed: int = EIGHT_BALL,
    *,
    clock: Clock = SYSTEM_CLOCK,
    store: Database | None = None,
) -> FastAPI:
    """The app, every new room racked with `seed` (see `games`)."""
    return create_app(settings, store=store, clock=clock, seeds=SeedSource.fixed(seed))


def make_client(settings: Settings, seed: int = EIGHT_BALL, **changes: Any) -> TestClient:
    """A TestClient (use it in `with`) of `app_with(settings.replace(**changes), seed)`."""
    return TestClient(app_with(settings.replace(**changes), seed))


def create_room(http: httpx.Client, game: str = "eight_ball", **extra: Any) -> str:
    response = http.post("/api/rooms", json={"game": game, **extra})
    assert response.status_code == 201, response.text
    return response.json()["room_id"]


def join(http: httpx.Client, room_id: str, name: str) -> dict:
    response = http.post(f"/api/rooms/{room_id}/join", json={"name": name})
    assert response.status_code == 200, response.text
    return response.json()


def seated_room(http: httpx.Client, game: str = "eight_ball", **extra: Any) -> tuple[str, str, str]:
    """A room with Ana in seat 0 and Ben in seat 1: (room_id, Ana's token, Ben's token)."""
    room_id = create_room(http, game, **extra)
    a = join(http, room_id, "Ana")
    b = join(http, room_id, "Ben")
    assert (a["seat"], b["seat"]) == (0, 1)
    return room_id, a["token"], b["token"]


def connect(
    client: TestClient, room_id: str, token: str | None = None, **kwargs: Any
) -> WebSocketTestSession:
    """A room socket whose `receive_json` also reads the binary `motion` message (decoded:
    `messages.receive_any`)."""
    url = f"/ws/rooms/{room_id}" + (f"?token={token}" if token else "")
    session = client.websocket_connect(url, **kwargs)
    session.receive_json = functools.partial(receive_any, session)  # type: ignore[method-assign]
    return session


def place_cue(shooter: Socket, x: float, y: float) -> dict:
    """Ball in hand: put the cue ball at (x, y); returns the `state` the shooter gets."""
    shooter.send_json({"type": "place_cue", "x": x, "y": y})
    reply = receive_until(shooter, ("state", "error"))[-1]
    assert reply["type"] == "state", reply
    return reply


def play_shot(
    players: Sequence[Socket],
    watcher: Socket,
    state: dict,
    shot: Shot | dict,
    place: tuple[float, float] | None = None,
) -> tuple[dict, list[dict], dict]:
    """The seat whose turn `state` shows plays `shot`, first putting the cue ball at `place`
    (ball in hand). Returns the `state` the shot was taken from, what `watcher` saw of the
    shot up to its `shot_result`, and the `state` after it."""
    shooter = players[state["match"]["turn"]]
    if place is not None:
        reply = place_cue(shooter, *place)
        state = reply if watcher is shooter else receive_until(watcher, "state")[-1]
    shooter.send_json(shot if isinstance(shot, dict) else shoot_message(shot))
    seen = receive_until(watcher, "state")
    assert any(m["type"] == "shot_result" for m in seen), seen
    return state, seen[:-1], seen[-1]
