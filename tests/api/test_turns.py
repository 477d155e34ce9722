"""Turn enforcement, the shot clock, conceding, rematch and reconnection grace."""

from __future__ import annotations

import pytest

from tests.support.games import BREAK_MESSAGE, EIGHT_BALL_BREAK_BALL
from tests.support.messages import (
    errors_in,
    greet,
    of_type,
    receive_until,
    roundtrip,
    state_where,
)
from tests.support.rooms import connect, create_room, join, make_client, seated_room

pytestmark = pytest.mark.timeout(60)


def test_only_the_player_whose_turn_it_is_may_act(client):
    room_id, ta, tb = seated_room(client)
    with (
        connect(client, room_id, ta) as a,
        connect(client, room_id, tb) as b,
        connect(client, room_id) as s,
    ):
        for ws in (a, b, s):
            greet(ws)
        before = client.get(f"/api/rooms/{room_id}").json()["state"]
        for ws, payload, code in [
            (b, BREAK_MESSAGE, "not_your_turn"),
            (b, {"type": "place_cue", "x": 0.4, "y": 0.5}, "not_your_turn"),
            (b, {"type": "aim", "angle": 0.0, "power": 0.5}, "not_your_turn"),
            (s, BREAK_MESSAGE, "spectator"),
            (s, {"type": "place_cue", "x": 0.4, "y": 0.5}, "spectator"),
            (s, {"type": "call", "pocket": 2}, "spectator"),
            (s, {"type": "concede"}, "spectator"),
            (s, {"type": "rematch"}, "spectator"),
            (a, {"type": "rematch"}, "match_not_over"),
            (a, {"type": "rerack"}, "not_practice"),
            (a, {"type": "decide", "option": "accept"}, "no_decision"),
        ]:
            errors = errors_in(roundtrip(ws, payload))
            assert [e["code"] for e in errors] == [code], payload
            assert errors[0]["ref"] == payload["type"]
        after = client.get(f"/api/rooms/{room_id}").json()["state"]
        assert after["balls"] == before["balls"] and after["match"] == before["match"]

        a.send_json(BREAK_MESSAGE)  # seat 0 may; while the balls roll nobody may act
        assert errors_in(roundtrip(a, BREAK_MESSAGE))[0]["code"] == "balls_moving"
        assert errors_in(roundtrip(b, BREAK_MESSAGE))[0]["code"] == "balls_moving"
        stream = receive_until(a, "state")
        (result,) = of_type(stream, "shot_result")
        assert result["outcome"]["pocketed"] == [EIGHT_BALL_BREAK_BALL]
        assert stream[-1]["match"]["turn"] == 0  # a ball dropped: Ana again, not Ben
        assert (
            errors_in(roundtrip(b, {"type": "shoot", "angle": 1.0, "speed": 2.0}))[0]["code"]
            == "not_your_turn"
        )


def test_aim_is_relayed_to_the_others_not_the_sender(client):
    room_id, ta, tb = seated_room(client)
    with connect(client, room_id, ta) as a, connect(client, room_id, tb) as b:
        greet(a)
        greet(b)
        a.send_json({"type": "aim", "angle": 0.25, "power": 0.6, "tip": [0.1, -0.2]})
        aim = next(m for m in receive_until(b, "aim") if m["type"] == "aim")
        assert aim == {"type": "aim", "seat": 0, "angle": 0.25, "power": 0.6, "tip": [0.1, -0.2]}
        assert all(m["type"] != "aim" for m in roundtrip(a, {"type": "sync"}))


def test_waiting_room_refuses_play_but_allows_chat(client):
    room_id = create_room(client)
    token = join(client, room_id, "Ana")["token"]
    with connect(client, room_id, token) as a:
        _, state = greet(a)
        assert state["phase"] == "waiting" and state["match"] is None
        assert errors_in(roundtrip(a, BREAK_MESSAGE))[0]["code"] == "not_started"
        chat = [m for m in roundtrip(a, {"type": "chat", "text": "anyone?"}) if m["type"] == "chat"]
        assert chat[0]["name"] == "Ana" and chat[0]["text"] == "anyone?"
        join(client, room_id, "Ben")  # the match starts: everyone gets a new state
        state = receive_until(a, "state")[-1]
        assert state["phase"] == "aiming" and state["match"]["players"] == ["Ana", "Ben"]


def test_shot_clock_passes_the_turn_with_a_foul(settings):
    with make_client(settings, min_shot_clock=0.1) as client:
        room_id, ta, tb = seated_room(client, shot_clock=0.4)
        with connect(client, room_id, ta) as a, connect(client, room_id, tb) as b:
            _, state = greet(a)
            greet(b)
            assert state["clock"]["seat"] == 0 and state["clock"]["limit"] == 0.4
            result = receive_until(a, "shot_result")[-1]
            assert result["cause"] == "timeout" and result["shot"] is None
            assert [f["code"] for f in result["outcome"]["fouls"]] == ["shot_clock"]
            state = receive_until(a, "state")[-1]
            assert state["match"]["turn"] == 1 and state["clock"]["seat"] == 1
            assert errors_in(roundtrip(a, BREAK_MESSAGE))[0]["code"] == "not_your_turn"


def test_concede_then_rematch(client):
    room_id, ta, tb = seated_room(client)  # race to 1
    with connect(client, room_id, ta) as a, connect(client, room_id, tb) as b:
        greet(a)
        greet(b)
        b.send_json({"type": "concede"})
        result = receive_until(a, "shot_result")[-1]
        assert result["cause"] == "concede" and result["match_over"]
        assert result["match_winner"] == 0 and result["score"] == [1, 0]
        state = receive_until(a, "state")[-1]
        assert state["phase"] == "over" and state["room"]["status"] == "finished"
        assert errors_in(roundtrip(a, BREAK_MESSAGE))[0]["code"] == "match_over"
        a.send_json({"type": "rematch"})
        assert state_where(b, lambda st: st["room"]["rematch"])["room"]["rematch"] == [0]
        b.send_json({"type": "rematch"})
        state = state_where(a, lambda st: st["phase"] == "aiming")
        assert state["match"]["score"] == [0, 0] and state["room"]["rematch"] == []


def test_player_who_reconnects_within_grace_keeps_playing(settings):
    """Ben drops and comes back within the grace period. Then a second room is seated and
    nobody connects to it: its grace timers started after Ben's, so when it forfeits,
    Ben's period is over too (no sleeping for a guessed while). Ana connects before Ben
    takes the last seat, so her own grace never runs."""
    with make_client(settings, grace=1.0) as client:
        room_id = create_room(client, shot_clock=0)
        ta = join(client, room_id, "Ana")["token"]
        with connect(client, room_id, ta) as a:
            greet(a)
            tb = join(client, room_id, "Ben")["token"]
            with connect(client, room_id, tb) as b:
                greet(b)
            presence = receive_until(a, "presence")
            while presence[-1]["players"][1]["connected"]:
                presence = receive_until(a, "presence")
            assert presence[-1]["grace"][0]["seat"] == 1
            with connect(client, room_id, tb) as b:
                _, state = greet(b)
                assert state["grace"] == [] and state["room"]["players"][1]["connected"]
                empty_id, _, _ = seated_room(client, shot_clock=0)
                with connect(client, empty_id) as watcher:
                    greet(watcher)
                    result = receive_until(watcher, "shot_result")[-1]
                    assert result["cause"] == "forfeit"
                got = roundtrip(b, {"type": "sync"})
                assert of_type(got, "shot_result") == []  # nothing was forfeited here
                assert got[-1]["phase"] == "aiming" and got[-1]["match"]["score"] == [0, 0]


def test_player_who_stays_away_forfeits_a_frame_per_grace_period(settings):
    """Ana is at the table before Ben takes the last seat: the grace periods start when
    the room is full, so a player seated first and slower to connect than the short grace
    would forfeit a frame of her own."""
    with make_client(settings, grace=0.3) as client:
        room_id = create_room(client, shot_clock=0, race_to=2)
        ta = join(client, room_id, "Ana")["token"]
        with connect(client, room_id, ta) as a:
            greet(a)
            tb = join(client, room_id, "Ben")["token"]
            with connect(client, room_id, tb) as b:
                greet(b)
            first = receive_until(a, "shot_result")[-1]
            assert first["cause"] == "forfeit" and first["outcome"]["shooter"] == 1
            assert "left the table" in first["outcome"]["message"]
            assert first["score"] == [1, 0] and not first["match_over"]
            state = receive_until(a, "state")[-1]
            assert state["grace"][0]["seat"] == 1  # the next frame is at stake
            second = receive_until(a, "shot_result")[-1]
            assert second["cause"] == "forfeit" and second["score"] == [2, 0]
            assert second["match_over"] and second["match_winner"] == 0


def test_second_socket_for_a_seat_replaces_the_first(client):
    from starlette.websockets import WebSocketDisconnect

    room_id, ta, _ = seated_room(client)
    with connect(client, room_id, ta) as first:
        greet(first)
        with connect(client, room_id, ta) as second:
            welcome, _ = greet(second)
            assert welcome["seat"] == 0
            with pytest.raises(WebSocketDisconnect) as closed:
                for _ in range(20):
                    first.receive_json()
            assert closed.value.code == 4000
            assert roundtrip(second, {"type": "sync"})[-1]["room"]["players"][0]["connected"]


def test_practice_allows_ball_in_hand_at_will_and_rerack(client):
    room_id = create_room(client, "practice")
    token = join(client, room_id, "Pia")["token"]
    with connect(client, room_id, token) as p:
        _, state = greet(p)
        assert state["clock"] is None
        got = roundtrip(p, {"type": "place_cue", "x": 1.0, "y": 0.3})
        state = [m for m in got if m["type"] == "state"][-1]
        assert state["balls"][0][:3] == [0, 1000, 300]
        p.send_json({"type": "shoot", "angle": 0.5, "speed": 3.0})
        outcome = receive_until(p, "shot_result")[-1]["outcome"]
        assert (outcome["fouls"], outcome["continues"], outcome["ball_in_hand"]) == (
            [],
            True,
            "anywhere",
        )
        assert receive_until(p, "state")[-1]["balls"][0][:3] != [0, 1000, 300]
        got = roundtrip(p, {"type": "rerack"})
        assert [m for m in got if m["type"] == "state"][-1]["balls"][0][:3] == [0, 635, 635]
