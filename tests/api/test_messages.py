"""Every message the server sends matches its model in `server.protocol.outbound`.

A real game through the TestClient (welcome, state, presence, chat, aim, pong, error, and a
shot's frames, events and `shot_result` for a shot, a concession, a timeout and a forfeit)
and a stored shot's replay stream: each message is validated against the union a client
parses, and every member of the union is seen at least once, so a new message type cannot
go untested. The clock is a `ManualClock`: the times in the messages are known exactly.
"""

from __future__ import annotations

import json
import typing
from typing import Any

import pytest
from fastapi.testclient import TestClient

from server.protocol.outbound import (
    AnyReplayMessage,
    AnyServerMessage,
    replay_messages,
    server_messages,
)
from server.rooms.clock import ManualClock
from tests.support.games import BREAK_MESSAGE, EIGHT_BALL_BREAK_BALL
from tests.support.messages import errors_in, greet, of_type, receive_until, roundtrip
from tests.support.rooms import app_with, connect, seated_room

pytestmark = pytest.mark.timeout(60)
START = 1_767_000_000.0


def members(union: Any) -> set[type]:
    """The models of an `Annotated[A | B | ..., Field(discriminator=...)]` union."""
    inner = typing.get_args(union)[0]
    return set(typing.get_args(inner))


class Recorded:
    """A TestClient socket that keeps every message it receives."""

    def __init__(self, ws: Any, log: list[dict]) -> None:
        self.ws = ws
        self.log = log

    def send_json(self, data: Any) -> None:
        self.ws.send_json(data)

    def send_text(self, data: str) -> None:
        self.ws.send_text(data)

    def receive_json(self) -> Any:
        message = self.ws.receive_json()
        self.log.append(message)
        return message


def test_every_server_message_and_replay_line_matches_its_model(settings) -> None:
    clock = ManualClock(now=START)
    seen: list[dict] = []
    settings = settings.replace(grace=2.0, min_shot_clock=0.1)
    with TestClient(app_with(settings, clock=clock.clock)) as client:
        room_id, ta, tb = seated_room(client, shot_clock=0, race_to=2)
        with (
            connect(client, room_id, ta) as wa,
            connect(client, room_id, tb) as wb,
            connect(client, room_id) as ws,
        ):
            a, b, s = (Recorded(w, seen) for w in (wa, wb, ws))
            welcome, state = greet(a)
            assert welcome["server_time"] == START and state["phase"] == "aiming"
            greet(b)
            greet(s)

            clock.advance(2.5)
            chat = of_type(roundtrip(s, {"type": "chat", "text": "good luck"}), "chat")
            assert chat[0]["at"] == START + 2.5 and chat[0]["name"] == "spectator"
            a.send_json({"type": "aim", "angle": 0.1, "power": 0.5, "tip": [0.0, 0.1]})
            assert receive_until(b, "aim")[-1]["seat"] == 0
            a.send_json({"type": "ping", "id": 7})
            pong = receive_until(a, "pong")[-1]
            assert pong == {"type": "pong", "id": 7, "server_time": START + 2.5}
            assert errors_in(roundtrip(b, BREAK_MESSAGE))[0]["code"] == "not_your_turn"

            a.send_json(BREAK_MESSAGE)
            shot = receive_until(s, "state")
            assert [m["type"] for m in shot[-2:]] == ["shot_result", "state"]
            assert shot[-2]["cause"] == "shot" and shot[-2]["outcome"]["pocketed"] == [
                EIGHT_BALL_BREAK_BALL
            ]
            b.send_json({"type": "concede"})
            conceded = receive_until(s, "state")
            assert of_type(conceded, "shot_result")[0]["cause"] == "concede"
            assert conceded[-1]["match"]["score"] == [1, 0]

        timed_id, tc, _ = seated_room(client, shot_clock=0.3)
        with connect(client, timed_id, tc) as wc:
            c = Recorded(wc, seen)
            greet(c)
            assert receive_until(c, "shot_result")[-1]["cause"] == "timeout"

        empty_id, _, _ = seated_room(client, shot_clock=0)  # nobody comes: a forfeit
        with connect(client, empty_id) as we:
            assert receive_until(Recorded(we, seen), "shot_result")[-1]["cause"] == "forfeit"

        (match,) = [
            m for m in client.get("/api/matches").json()["matches"] if m["room_id"] == room_id
        ]
        reply = client.get(f"/api/matches/{match['id']}/shots/1/replay", params={"pace": 50})
        assert reply.status_code == 200
        assert reply.headers["content-type"].startswith("application/x-ndjson")
        lines = [json.loads(line) for line in reply.text.splitlines()]

    assert of_type(seen, "motion")  # binary, checked byte by byte in test_motion_codec
    texts = [m for m in seen if m["type"] != "motion"]
    models = [server_messages.validate_python(m) for m in texts]
    for message, model in zip(texts, models, strict=True):
        assert model.type == message["type"]
    assert {type(m) for m in models} == members(AnyServerMessage)
    assert {m["cause"] for m in of_type(seen, "shot_result")} == {
        "shot",
        "concede",
        "timeout",
        "forfeit",
    }

    replayed = [replay_messages.validate_python(line) for line in lines]
    assert {type(m) for m in replayed} == members(AnyReplayMessage)
    assert lines[-1]["type"] == "shot_result" and lines[-1]["outcome"]["pocketed"] == [
        EIGHT_BALL_BREAK_BALL
    ]
    assert lines[-1]["replay"] == {"match": match["id"], "n": 1}
