"""Match history through the real API: a match played over the WebSocket is stored with its
games and shots; `GET /api/matches`, `GET /api/matches/{id}` and the replay of a shot, which
equals the live stream message for message and the engine's result bit for bit."""

from __future__ import annotations

import base64
import json
import math

import pytest
from fastapi.testclient import TestClient

from server.engine import BallSet, Table, simulate
from server.protocol.motion import decode_motion
from server.rooms.replay import resimulate
from server.store.records import ShotRecord
from tests.support.games import (
    BREAK,
    EIGHT_BALL_BREAK_BALL,
    EIGHT_BALL_GROUP_BALL,
    EIGHT_BALL_GROUP_SHOT,
    EIGHT_BALL_PLACE,
    EIGHT_BALL_SCRATCH,
)
from tests.support.messages import greet, receive_until, shot_payload
from tests.support.rooms import app_with, connect, play_shot, seated_room

pytestmark = pytest.mark.timeout(120)
# The game of `games.EIGHT_BALL`: the break pockets a ball, Ana's next shot scratches, Ben
# puts the cue ball down and pockets a ball. (shot, where the cue ball is put first)
SHOTS = [(BREAK, None), (EIGHT_BALL_SCRATCH, None), (EIGHT_BALL_GROUP_SHOT, EIGHT_BALL_PLACE)]
POCKETED = [[EIGHT_BALL_BREAK_BALL], [0], [EIGHT_BALL_GROUP_BALL]]


def test_a_played_match_is_listed_detailed_and_replayed_exactly(settings):
    with TestClient(app_with(settings)) as client:
        room_id, ta, tb = seated_room(client, race_to=1)
        with (
            connect(client, room_id, ta) as a,
            connect(client, room_id, tb) as b,
            connect(client, room_id) as s,
        ):
            _, state = greet(s)
            first_state = state
            live, befores = [], []
            for shot, place in SHOTS:
                before, seen, state = play_shot((a, b), s, state, shot, place)
                befores.append(before)
                live.append((seen, state))
            assert state["match"]["turn"] == 1  # Ben took a group and plays on
            b.send_json({"type": "concede"})  # ... but concedes
            final = receive_until(s, "state")[-1]
        assert final["phase"] == "over"

        listing = client.get("/api/matches").json()["matches"]
        assert len(listing) == 1
        summary = listing[0]
        assert summary["room_id"] == room_id and summary["status"] == "finished"
        assert summary["players"] == ["Ana", "Ben"] and summary["game"] == "eight_ball"
        assert summary["winner"] == 0 and summary["winner_name"] == "Ana"
        assert summary["score"] == final["match"]["score"] == [1, 0]
        assert summary["reason"] == final["match"]["match_reason"]
        assert (summary["games"], summary["shots"]) == (1, 3)
        assert summary["finished_at"] >= summary["started_at"]
        assert client.get("/api/matches?status=playing").json()["matches"] == []

        detail = client.get(f"/api/matches/{summary['id']}").json()
        assert [g["cause"] for g in detail["games"]] == ["concede"]
        assert detail["games"][0]["winner"] == 0
        shots = detail["shots"]
        assert [s["n"] for s in shots] == [1, 2, 3]
        # what a replay draws: the table as `state` gives it and the balls each shot was taken
        # from (after any ball-in-hand placement)
        assert detail["geometry"] == first_state["table"]
        assert [stored["b"] for stored in shots] == [st["balls"] for st in befores]
        for stored, (shot, _), (seen, after), pocketed in zip(
            shots, SHOTS, live, POCKETED, strict=True
        ):
            result = next(m for m in seen if m["type"] == "shot_result")
            assert stored["shot"] == {
                "angle": shot.angle,
                "speed": shot.speed,
                "tip": list(shot.tip),
            }
            assert stored["outcome"] == result["outcome"]
            assert result["outcome"]["pocketed"] == pocketed
            assert stored["shot_id"] == result["shot"]

            # the replay stream is the live stream, message for message
            reply = client.get(stored["replay"], params={"pace": 100})
            assert reply.status_code == 200
            assert reply.headers["content-type"].startswith("application/x-ndjson")
            replayed = [json.loads(line) for line in reply.text.splitlines()]
            (live,) = [m for m in seen if m["type"] == "motion"]
            assert [m["type"] for m in replayed] == ["motion", "shot_result"]
            again_motion = decode_motion(base64.b64decode(replayed[0]["data"]))
            assert shot_payload(again_motion) == shot_payload(live)  # the very bytes shown
            assert [m["seq"] for m in replayed] == list(range(1, len(replayed) + 1))
            assert replayed[-1]["type"] == "shot_result"
            assert replayed[-1]["outcome"] == result["outcome"]

            # and the engine's floats are the same bit for bit: the table after the shot
            # (exact floats in the next `state`) is the re-simulated final table
            record = ShotRecord(
                summary["id"],
                stored["n"],
                stored["shot_id"],
                stored["game"],
                stored["seat"],
                stored["shot"],
                stored["table"],
                stored["balls"],
                stored["outcome"],
                stored["played_at"],
            )
            again = resimulate(record)
            spotted = set(result["outcome"]["spotted"]) | {0}
            shown = {b["id"]: (b["x"], b["y"]) for b in after["match"]["balls"]}
            for i, ball in enumerate(again.final.ids.tolist()):
                if ball not in spotted and again.final.on_table[i]:
                    assert shown[ball] == tuple(again.final.positions[i].tolist())
            direct = simulate(Table(*stored["table"]), BallSet.from_dict(stored["balls"]), shot)
            assert direct.frames.positions.tobytes() == again.frames.positions.tobytes()


def test_unknown_match_and_shot_are_404_and_bad_queries_422(settings):
    with TestClient(app_with(settings)) as client:
        assert client.get("/api/matches").json() == {"matches": []}
        missing = client.get("/api/matches/999")
        assert missing.status_code == 404
        assert missing.json()["detail"]["code"] == "unknown_match"
        assert client.get("/api/matches/999/shots/1/replay").status_code == 404
        assert client.get("/api/matches/abc").status_code == 422
        assert client.get("/api/matches?limit=0").status_code == 422
        assert client.get("/api/matches?status=lost").status_code == 422
        assert client.get("/api/matches/1/shots/1/replay?pace=nan").status_code == 422


def test_a_ball_moved_by_the_rules_shows_one_cel_live_and_stored(settings):
    """A re-spotted ball was never in a frame where it now lies: the live `state` and the
    stored table both draw its cel from the angle it rolled (its phase)."""
    with TestClient(app_with(settings)) as client:
        room_id, ta, tb = seated_room(client, race_to=1)
        balls = client.app.state.registry.get(room_id).room.match.game.balls
        balls.phases[balls.index(8)] = 2.5  # rolled 2.5 rad, then spotted by the rules
        with (
            connect(client, room_id, ta) as a,
            connect(client, room_id, tb) as b,
            connect(client, room_id) as s,
        ):
            _, state = greet(s)
            before, _, _ = play_shot((a, b), s, state, BREAK)
        eight = next(row for row in before["balls"] if row[0] == 8)
        assert eight[3] == int(2.5 / (2 * math.pi) * 16)  # cel 6 of 16
        match_id = client.get("/api/matches").json()["matches"][0]["id"]
        stored = client.get(f"/api/matches/{match_id}").json()["shots"][0]
        assert stored["b"] == before["balls"]
