"""A person plays the computer over the real WebSocket: the computer takes the second seat,
shows its cue moving, and plays its turns through the same room actions as a person."""

from __future__ import annotations

import asyncio
import json
import logging
import os
import subprocess
import sys
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import pytest
from fastapi.testclient import TestClient
from starlette.testclient import WebSocketTestSession

from server.ai import Bot, play_turn
from server.ai.analysis import positions
from server.app import create_app
from server.codec import from_data, to_data
from server.engine import Shot
from server.rooms import SeedSource
from server.rooms.analyses import stored_shot
from server.rooms.computer import THREAD_PLAN_NOTE, plan_turn
from server.rules import Game
from server.store import Database
from tests.support.games import BREAK_MESSAGE, EIGHT_BALL
from tests.support.settings import settings_in

pytestmark = pytest.mark.timeout(180)


@pytest.fixture
def client(tmp_path: Path) -> Iterator[TestClient]:
    # The longest clock: streamed 20 times faster, the default one gives a seat 3 s, and on
    # a loaded machine the first plan (the planner processes starting) can take longer;
    # these tests are about what the computer does, not about its clock.
    settings = settings_in(tmp_path, computer_pause=0.0, shot_clock=600.0)
    with TestClient(create_app(settings, seeds=SeedSource.fixed(EIGHT_BALL))) as c:
        yield c


def next_json(ws: WebSocketTestSession) -> dict[str, Any]:
    """The next JSON message (frames may come as binary messages: skipped here)."""
    while True:
        message = ws.receive()
        if message.get("text") is not None:
            return json.loads(message["text"])
        if message["type"] == "websocket.close":
            raise AssertionError(f"closed: {message}")


def computer_room(client: TestClient) -> tuple[str, str]:
    """A room against the club level with Ana in the first seat: (room id, her token)."""
    created = client.post(
        "/api/rooms", json={"game": "eight_ball", "opponent": "club", "listed": False}
    )
    assert created.status_code == 201 and created.json()["opponent"] == "club"
    room_id = created.json()["room_id"]
    ana = client.post(f"/api/rooms/{room_id}/join", json={"name": "Ana"}).json()
    assert ana["seat"] == 0  # the person breaks
    return room_id, ana["token"]


def play_until_the_computer_shoots(ws: WebSocketTestSession) -> tuple[list[dict], int]:
    """Ana breaks and misses until the computer has played a shot: (the shot results, the
    computer's aim relays seen)."""
    while next_json(ws)["type"] != "presence":
        pass
    ws.send_json(BREAK_MESSAGE)  # the rack's break: legal, then a miss hands over
    results: list[dict] = []
    aims = 0
    while 1 not in (r["outcome"]["shooter"] for r in results):
        message = next_json(ws)
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
    return results, aims


def test_the_computer_takes_the_second_seat_and_plays_its_turn(
    client: TestClient, caplog: pytest.LogCaptureFixture
):
    room_id, token = computer_room(client)
    room = client.get(f"/api/rooms/{room_id}").json()
    assert room["players"] == ["Ana", "Computer (club)"] and room["status"] == "playing"
    url = f"/ws/rooms/{room_id}?token={token}"
    with (
        caplog.at_level(logging.WARNING, "server.rooms.computer"),
        client.websocket_connect(url) as ws,
    ):
        results, aims = play_until_the_computer_shoots(ws)
    assert results[-1]["outcome"]["shooter"] == 1  # the computer shot
    assert aims >= 3  # and its cue was seen moving first
    assert not caplog.records  # in its planner process: nothing starved it here


def test_the_computers_planned_stroke_is_kept_with_its_shot_and_judged(client: TestClient):
    """The computer's stroke is its plan plus its arm's error; the room stores the plan
    beside it, and the analysis judges the plan (as it judges a person's stroke as sent)."""
    room_id, token = computer_room(client)
    with client.websocket_connect(f"/ws/rooms/{room_id}?token={token}") as ws:
        play_until_the_computer_shoots(ws)
    found = client.get(f"/api/matches?room={room_id}&limit=1").json()["matches"]
    match_id = found[0]["id"]
    shots = client.get(f"/api/matches/{match_id}").json()["shots"]
    ana = [s for s in shots if s["seat"] == 0]
    computer = [s for s in shots if s["seat"] == 1]
    assert ana and computer
    assert all(s["intended"] is None for s in ana)
    for s in computer:
        assert set(s["intended"]) == {"angle", "speed", "tip"}
        assert s["intended"] != s["shot"]  # the club level's arm strays from its plan

    store: Database = client.app.state.store  # type: ignore[attr-defined]
    records = store.run(lambda repo: repo.shots(match_id))
    stored = [stored_shot(r) for r in records]
    judged = {b.stored.n: b.stroke for b in positions("eight_ball", found[0]["players"], stored)}
    for s in shots:
        meant = s["shot"] if s["intended"] is None else s["intended"]
        assert judged[s["n"]] == from_data(Shot, meant)


@contextmanager
def every_core_busy() -> Iterator[None]:
    """A busy loop at normal priority on every core this process may use: the planners, at
    Linux's idle class, get no CPU while these run."""
    cores = len(os.sched_getaffinity(0))
    loops = [subprocess.Popen([sys.executable, "-c", "while True: pass"]) for _ in range(cores)]
    try:
        yield
    finally:
        for loop in loops:
            loop.kill()
            loop.wait()


@pytest.mark.slow  # many seconds: not in scripts/test --quick
def test_the_computer_still_moves_when_other_work_starves_its_planner(
    tmp_path: Path, caplog: pytest.LogCaptureFixture
):
    """Its planner process runs at the idle class so as never to slow the rooms; when
    other work keeps every core busy it gets no CPU, and the turn is planned in a thread
    of the server instead of never (before, a CI run beside a benchmark timed out here)."""
    settings = settings_in(
        tmp_path, computer_pause=0.0, shot_clock=600.0, computer_workers=1, computer_starved=2.0
    )
    app = create_app(settings, seeds=SeedSource.fixed(EIGHT_BALL))
    log = caplog.at_level(logging.WARNING, "server.rooms.computer")
    with log, TestClient(app) as client, every_core_busy():
        room_id, token = computer_room(client)
        with client.websocket_connect(f"/ws/rooms/{room_id}?token={token}") as ws:
            results, _ = play_until_the_computer_shoots(ws)
    assert results[-1]["outcome"]["shooter"] == 1
    # `bench.load` counts these warnings in the server's log.
    starved = [r.getMessage() for r in caplog.records if THREAD_PLAN_NOTE in r.getMessage()]
    assert starved and "the machine is busy with other work" in starved[0]


def test_the_computer_is_only_for_real_games_at_known_levels(client: TestClient):
    bad_level = client.post("/api/rooms", json={"game": "eight_ball", "opponent": "god"})
    practice = client.post("/api/rooms", json={"game": "practice", "opponent": "pro"})
    assert bad_level.status_code == 422 and practice.status_code == 422


def play_hint(client: TestClient, room_id: str, token: str, hint: dict) -> dict:
    """Place the cue ball where the hint has it and play its shot; the shot's result."""
    with client.websocket_connect(f"/ws/rooms/{room_id}?token={token}") as ws:
        x, y = hint["place"]
        ws.send_json({"type": "place_cue", "x": x, "y": y})
        ws.send_json(
            {"type": "shoot", "angle": hint["angle"], "speed": hint["speed"], "tip": hint["tip"]}
        )
        while (message := next_json(ws))["type"] != "shot_result":
            assert message["type"] != "error", message
    return message


@pytest.mark.slow  # many seconds: not in scripts/test --quick
def test_a_hint_shows_the_strongest_plan_without_playing_it(client: TestClient):
    room_id = client.post("/api/rooms", json={"game": "practice", "listed": False}).json()[
        "room_id"
    ]
    ana = client.post(f"/api/rooms/{room_id}/join", json={"name": "Ana"}).json()
    # A fresh rack: the plan is the break (the computer's own), which the room accepts.
    rack = client.post(f"/api/rooms/{room_id}/hint", json={"token": ana["token"]}).json()
    assert rack["kind"] == "break" and rack["place"] is not None and rack["speed"] >= 10.0
    assert play_hint(client, room_id, ana["token"], rack)["outcome"]["shooter"] == 0
    before = client.get(f"/api/rooms/{room_id}").json()["state"]
    reply = client.post(f"/api/rooms/{room_id}/hint", json={"token": ana["token"]})
    assert reply.status_code == 200, reply.text
    hint = reply.json()
    assert hint["level"] == "pro" and hint["kind"] in ("pot", "safety", "kick")
    assert hint["place"] is not None and 0 < hint["speed"] <= 12.0  # ball in hand in practice
    assert len(hint["tip"]) == 2
    assert (
        hint["via"] in ("direct", "bank", "combo", "carom", "billiard")
        if hint["kind"] == "pot"
        else not hint["via"]
    )
    # Nothing was played: the table and the turn are as they were.
    assert client.get(f"/api/rooms/{room_id}").json()["state"] == before
    # The plan is one the room accepts: place the cue ball there and play it.
    assert play_hint(client, room_id, ana["token"], hint)["outcome"]["shooter"] == 0


def test_a_hint_is_for_the_player_of_a_practice_table(client: TestClient):
    practice = client.post("/api/rooms", json={"game": "practice", "listed": False}).json()
    client.post(f"/api/rooms/{practice['room_id']}/join", json={"name": "Ana"})
    wrong = client.post(f"/api/rooms/{practice['room_id']}/hint", json={"token": "nope"})
    assert wrong.status_code == 403 and wrong.json()["detail"]["code"] == "bad_token"
    game = client.post("/api/rooms", json={"game": "eight_ball", "listed": False}).json()
    bea = client.post(f"/api/rooms/{game['room_id']}/join", json={"name": "Bea"}).json()
    refused = client.post(f"/api/rooms/{game['room_id']}/hint", json={"token": bea["token"]})
    assert refused.status_code == 409 and refused.json()["detail"]["code"] == "not_practice"
    missing = client.post("/api/rooms/nosuchroom/hint", json={"token": bea["token"]})
    assert missing.status_code == 404


@pytest.mark.parametrize("workers", [0, 1])
def test_the_room_planner_plans_what_the_bot_plans_in_place(workers: int):
    """A planner process (or thread) gets the game's data and returns the very turn the bot
    plans on the game itself: the position, the level and the seed decide it."""
    game = Game.new("eight_ball", ["ana", "computer"], seed=5)
    bot = Bot("club", seed=9)
    play_turn(game, game.turn, bot.plan(game, game.turn))  # the break
    seat = game.decision.seat if game.decision else game.turn
    here = bot.plan(game, seat)
    there = asyncio.run(plan_turn("club", 9, to_data(game), seat, workers))
    assert there == here
