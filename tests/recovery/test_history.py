"""Match history through the real API: a match played over the WebSocket is stored with its
games and shots; `GET /api/matches`, `GET /api/matches/{id}` and the replay of a shot, which
equals the live stream message for message and the engine's result bit for bit."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from fastapi.testclient import TestClient

from server.engine import BallSet, Shot, Table, simulate
from server.store.records import ShotRecord
from server.rooms.replay import resimulate

from .conftest import app_on, shot_payload

pytestmark = pytest.mark.timeout(120)
SHOTS = [{"type": "shoot", "angle": 0.0, "speed": 9.0},
         {"type": "shoot", "angle": 2.2, "speed": 3.0, "tip": [0.1, -0.2]},
         {"type": "shoot", "angle": -0.9, "speed": 5.5}]


def ws_until(ws, kind: str) -> list[dict]:
    out = []
    while True:
        out.append(ws.receive_json())
        if out[-1]["type"] == kind:
            return out


def seated_match(client: TestClient) -> tuple[str, list[str]]:
    """An 8-ball race to 1 with Ana and Ben seated: the room id and their tokens."""
    room_id = client.post("/api/rooms", json={"game": "eight_ball", "race_to": 1}
                          ).json()["room_id"]
    tokens = [client.post(f"/api/rooms/{room_id}/join", json={"name": n}).json()["token"]
              for n in ("Ana", "Ben")]
    return room_id, tokens


def play_shot(players, spectator, state: dict,
              payload: dict) -> tuple[dict, list[dict], dict]:
    """The seat to act shoots (placing the cue ball first if it is in hand); returns the
    `state` the shot was taken from (after any placement), what the spectator saw of the
    shot and the `state` after it."""
    match = state["match"]
    if match["decision"] is not None:
        seat = match["decision"]["seat"]
        players[seat].send_json({"type": "decide", "option": match["decision"]["options"][0]})
        state = ws_until(spectator, "state")[-1]
        match = state["match"]
    shooter = players[match["turn"]]
    if not any(row[0] == 0 for row in state["balls"]):  # ball in hand: find a free spot
        for x, y in ((0.4, 0.3), (0.3, 1.0), (0.5, 0.9), (0.2, 0.2), (0.55, 0.5)):
            shooter.send_json({"type": "place_cue", "x": x, "y": y})
            reply = next(m for m in iter(shooter.receive_json, None)
                         if m["type"] in ("state", "error"))
            if reply["type"] == "state":
                state = ws_until(spectator, "state")[-1]
                break
    if match["requires_call"]:
        shooter.send_json({"type": "call", "pocket": 0})
        state = ws_until(spectator, "state")[-1]
    shooter.send_json(payload)
    seen = ws_until(spectator, "state")
    return state, seen[:-1], seen[-1]


def test_a_played_match_is_listed_detailed_and_replayed_exactly(settings, db_path: Path):
    with TestClient(app_on(settings, db_path)) as client:
        room_id, tokens = seated_match(client)
        url = f"/ws/rooms/{room_id}"
        with client.websocket_connect(f"{url}?token={tokens[0]}") as a, \
                client.websocket_connect(f"{url}?token={tokens[1]}") as b, \
                client.websocket_connect(url) as s:
            state = ws_until(s, "state")[-1]
            first_state = state
            live, befores = [], []
            for payload in SHOTS:
                before, seen, state = play_shot((a, b), s, state, payload)
                befores.append(before)
                live.append((seen, state))
            conceder = state["match"]["turn"]
            (a, b)[conceder].send_json({"type": "concede"})
            final = ws_until(s, "state")[-1]
        assert final["phase"] == "over"

        listing = client.get("/api/matches").json()["matches"]
        assert len(listing) == 1
        summary = listing[0]
        assert summary["room_id"] == room_id and summary["status"] == "finished"
        assert summary["players"] == ["Ana", "Ben"] and summary["game"] == "eight_ball"
        assert summary["winner"] == 1 - conceder
        assert summary["score"] == final["match"]["score"]
        assert summary["reason"] == final["match"]["match_reason"]
        assert (summary["games"], summary["shots"]) == (1, 3)
        assert summary["finished_at"] >= summary["started_at"]
        assert client.get("/api/matches?status=playing").json()["matches"] == []

        detail = client.get(f"/api/matches/{summary['id']}").json()
        assert [g["cause"] for g in detail["games"]] == ["concede"]
        assert detail["games"][0]["winner"] == 1 - conceder
        shots = detail["shots"]
        assert [s["n"] for s in shots] == [1, 2, 3]
        # what a replay draws: the table as `state` gives it and the balls each shot was taken
        # from (after any ball-in-hand placement)
        assert detail["geometry"] == first_state["table"]
        assert [stored["b"] for stored in shots] == [st["balls"] for st in befores]
        for stored, payload, (seen, after) in zip(shots, SHOTS, live, strict=True):
            result = next(m for m in seen if m["type"] == "shot_result")
            assert stored["shot"]["angle"] == payload["angle"]
            assert stored["shot"]["speed"] == payload["speed"]
            assert stored["outcome"] == result["outcome"]
            assert stored["shot_id"] == result["shot"]

            # the replay stream is the live stream, message for message
            reply = client.get(stored["replay"], params={"pace": 100})
            assert reply.status_code == 200
            assert reply.headers["content-type"].startswith("application/x-ndjson")
            replayed = [json.loads(line) for line in reply.text.splitlines()]
            streamed = [m for m in seen if m["type"] in ("frame", "event")]
            again_msgs = [shot_payload(m) for m in replayed[:-1]]
            live_msgs = [shot_payload(m) for m in streamed]
            # a busy client may skip stale frames (droppable); everything it got is in the
            # replay, in the same order, and nothing but frames is missing
            assert is_subsequence(live_msgs, again_msgs)
            assert [m for m in again_msgs if m["type"] == "event"] == [
                m for m in live_msgs if m["type"] == "event"]
            assert again_msgs[-1] == live_msgs[-1] and live_msgs[-1]["last"]
            first = next(m for m in again_msgs if m["type"] == "frame")
            per_message = settings.frames_per_message
            assert [first["tick"], *(a["tick"] for a in first.get("ahead", ()))] == [
                6 * (k + 1) for k in range(per_message)]
            assert [m["seq"] for m in replayed] == list(range(1, len(replayed) + 1))
            assert replayed[-1]["type"] == "shot_result"
            assert replayed[-1]["outcome"] == result["outcome"]

            # and the engine's floats are the same bit for bit: the table after the shot
            # (exact floats in the next `state`) is the re-simulated final table
            record = ShotRecord(summary["id"], stored["n"], stored["shot_id"], stored["game"],
                                stored["seat"], stored["shot"], stored["table"],
                                stored["balls"], stored["outcome"], stored["played_at"])
            again = resimulate(record)
            spotted = set(result["outcome"]["spotted"]) | {0}
            shown = {b["id"]: (b["x"], b["y"]) for b in after["match"]["balls"]}
            for i, ball in enumerate(again.final.ids.tolist()):
                if ball not in spotted and again.final.on_table[i]:
                    assert shown[ball] == tuple(again.final.positions[i].tolist())
            direct = simulate(Table(*stored["table"]), BallSet.from_dict(stored["balls"]),
                              Shot(payload["angle"], payload["speed"],
                                   tuple(payload.get("tip", (0.0, 0.0)))))
            assert direct.frames.positions.tobytes() == again.frames.positions.tobytes()


def is_subsequence(part: list, whole: list) -> bool:
    it = iter(whole)
    return all(any(x == y for y in it) for x in part)


def test_unknown_match_and_shot_are_404_and_bad_queries_422(settings, db_path: Path):
    with TestClient(app_on(settings, db_path)) as client:
        assert client.get("/api/matches").json() == {"matches": []}
        missing = client.get("/api/matches/999")
        assert missing.status_code == 404
        assert missing.json()["detail"]["code"] == "unknown_match"
        assert client.get("/api/matches/999/shots/1/replay").status_code == 404
        assert client.get("/api/matches/abc").status_code == 422
        assert client.get("/api/matches?limit=0").status_code == 422
        assert client.get("/api/matches?status=lost").status_code == 422
        assert client.get("/api/matches/1/shots/1/replay?pace=nan").status_code == 422


def test_a_ball_moved_by_the_rules_shows_one_cel_live_and_stored(settings, db_path: Path):
    """A re-spotted ball was never in a frame where it now lies: the live `state` and the
    stored table both draw its cel from the angle it rolled (its phase)."""
    with TestClient(app_on(settings, db_path)) as client:
        room_id, tokens = seated_match(client)
        balls = client.app.state.registry.get(room_id).room.match.game.balls
        balls.phases[balls.index(8)] = 2.5  # rolled 2.5 rad, then spotted by the rules
        url = f"/ws/rooms/{room_id}"
        with client.websocket_connect(f"{url}?token={tokens[0]}") as a, \
                client.websocket_connect(f"{url}?token={tokens[1]}") as b, \
                client.websocket_connect(url) as s:
            ws_until(s, "state")
            s.send_json({"type": "sync"})
            state = ws_until(s, "state")[-1]
            before, _, _ = play_shot((a, b), s, state, SHOTS[0])
        eight = next(row for row in before["balls"] if row[0] == 8)
        assert eight[3] == int(2.5 / (2 * math.pi) * 16)  # cel 6 of 16
        match_id = client.get("/api/matches").json()["matches"][0]["id"]
        stored = client.get(f"/api/matches/{match_id}").json()["shots"][0]
        assert stored["b"] == before["balls"]
