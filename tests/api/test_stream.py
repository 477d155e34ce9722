"""A shot sent to the room: its `motion` message at the strike, `shot_result`, `state`."""

from __future__ import annotations

import time

import pytest

from tests.support.games import (
    BREAK_MESSAGE,
    EIGHT_BALL_BREAK_BALL,
    EIGHT_BALL_BREAK_SAYS,
    eight_ball_break_ticks,
)
from tests.support.messages import (
    assert_valid,
    drain_presence,
    greet,
    receive_until,
)
from tests.support.rooms import connect, make_client, seated_room

pytestmark = pytest.mark.timeout(120)


def test_break_is_streamed_to_both_players_and_a_spectator(settings):
    with make_client(settings, pace=4.0) as client:
        stream = _break_streamed(client)
    _check_break_stream(stream)


def _break_streamed(client) -> list[dict]:
    room_id, ta, tb = seated_room(client)
    with (
        connect(client, room_id, ta) as a,
        connect(client, room_id, tb) as b,
        connect(client, room_id) as s,
    ):
        welcomes = []
        for ws, pending in ((a, 2), (b, 1), (s, 0)):
            welcome, state = greet(ws)
            welcomes.append(welcome)
            drain_presence(ws, pending)
        assert [w["seat"] for w in welcomes] == [0, 1, None]
        assert welcomes[2]["role"] == "spectator"
        assert state["phase"] == "aiming" and state["match"]["turn"] == 0

        a.send_json(BREAK_MESSAGE)
        streams = [receive_until(ws, "state") for ws in (a, b, s)]
    assert streams[0] == streams[1] == streams[2]  # everyone sees the same stream
    return streams[0]


def _check_break_stream(stream: list[dict]) -> None:
    assert_valid(stream)
    seqs = [m["seq"] for m in stream]
    assert seqs == list(range(seqs[0], seqs[0] + len(seqs)))  # no gaps
    # The whole shot in one message at the strike, then the result and the table at rest.
    assert [m["type"] for m in stream] == ["motion", "shot_result", "state"]
    motion = stream[0]
    assert motion["shot"] == 1
    assert motion["duration"] == pytest.approx(eight_ball_break_ticks() / 120, abs=1e-6)

    tracks = {t["id"]: t for t in motion["tracks"]}
    assert sorted(tracks) == list(range(16))
    for track in tracks.values():
        assert track["t"][0] == 0.0 and track["t"] == sorted(track["t"])
        assert track["t"][-1] <= motion["duration"] + 1e-6
        assert all(-0.1 <= x <= 2.64 for x in track["x"])
        assert all(-0.1 <= y <= 1.37 for y in track["y"])
    cue = tracks[0]
    assert (cue["x"][0], cue["y"][0]) == (0.635, 0.635)  # from the head spot ...
    assert cue["x"][1] > 0.635 and len(cue["t"]) > 2  # ... along +x, and on
    dropped = [i for i, t in tracks.items() if t["pocket"] is not None]
    assert dropped == [EIGHT_BALL_BREAK_BALL]

    sounds = motion["sounds"]
    assert sounds[0]["kind"] == "strike" and sounds[0]["t"] == 0.0
    assert sounds[0]["speed"] == pytest.approx(9.0)
    kinds = {e["kind"] for e in sounds}
    assert {"strike", "ball", "cushion"} <= kinds and "rest" not in kinds
    assert any(e["kind"] == "ball" and 0 in e["ids"] for e in sounds)
    times = [e["t"] for e in sounds]
    assert times == sorted(times)
    pocket = [e for e in sounds if e["kind"] == "pocket"]
    assert [e["ids"] for e in pocket] == [[EIGHT_BALL_BREAK_BALL]]
    # The dropped ball's track ends where it drops, at its pocket sound's time.
    assert tracks[EIGHT_BALL_BREAK_BALL]["t"][-1] == pytest.approx(pocket[0]["t"], abs=2e-6)
    assert tracks[EIGHT_BALL_BREAK_BALL]["pocket"] == pocket[0]["target"]

    result, state = stream[-2], stream[-1]
    outcome = result["outcome"]
    assert result["shot"] == 1 and result["cause"] == "shot"
    assert (outcome["shooter"], outcome["pocketed"], outcome["fouls"]) == (
        0,
        [EIGHT_BALL_BREAK_BALL],
        [],
    )
    assert outcome["continues"] and outcome["next_turn"] == 0 and outcome["spotted"] == []
    assert outcome["message"] == EIGHT_BALL_BREAK_SAYS
    assert state["phase"] == "aiming" and state["shot"] is None
    assert state["match"]["turn"] == 0 and state["match"]["breaking"] is False
    assert len(state["balls"]) == 15
    for ball_id, x_mm, y_mm, _ in state["balls"]:  # the tracks end where the balls rest
        track = tracks[ball_id]
        assert abs(track["x"][-1] * 1000 - x_mm) <= 0.6
        assert abs(track["y"][-1] * 1000 - y_mm) <= 0.6


@pytest.mark.slow  # many seconds: not in scripts/test --quick
def test_member_joining_mid_shot_gets_state_and_the_motion(settings):
    """A late joiner gets where the shot is now (`state.shot.tick`) and the same motion
    message the others got at the strike, to play from that tick on."""
    with make_client(settings, pace=1.0) as client:
        room_id, ta, _ = seated_room(client)
        with connect(client, room_id, ta) as a:
            greet(a)
            a.send_json(BREAK_MESSAGE)
            sent = a.receive_json()
            assert sent["type"] == "motion"
            time.sleep(0.5)  # the break is being shown
            with connect(client, room_id) as s:
                welcome, state = greet(s)
                assert state["phase"] == "rolling"
                assert state["shot"]["id"] == 1 and state["shot"]["seat"] == 0
                assert (
                    30 <= state["shot"]["tick"] < state["shot"]["ticks"] == eight_ball_break_ticks()
                )
                assert state["match"]["turn"] == 0  # the match as it was at the strike
                assert state["match"]["balls"][EIGHT_BALL_BREAK_BALL]["on_table"]
                assert state["seq"] == welcome["seq"]
                rest = receive_until(s, "state")
            assert rest[0] == sent  # the very message, its seq from before we came
            assert [m["type"] for m in rest[1:]] == ["shot_result", "state"]
            assert rest[1]["seq"] == welcome["seq"] + 2  # after our own presence


def test_rest_state_is_the_same_over_http_and_websocket(client):
    room_id, ta, _ = seated_room(client)
    with connect(client, room_id, ta) as a:
        greet(a)
        a.send_json(BREAK_MESSAGE)
        final = receive_until(a, "state")[-1]
        http_state = client.get(f"/api/rooms/{room_id}").json()["state"]
    assert http_state["balls"] == final["balls"]
    assert http_state["match"] == final["match"]


def test_the_result_waits_for_the_motion_to_be_shown(settings):
    """The motion leaves at the strike; the outcome only once the shot has been played
    (`pace` 4: a quarter of its duration), so nobody learns it before seeing it."""
    with make_client(settings, pace=4.0) as client:
        room_id, ta, _ = seated_room(client)
        with connect(client, room_id, ta) as a:
            greet(a)
            a.send_json(BREAK_MESSAGE)
            motion = a.receive_json()
            started = time.monotonic()
            result = a.receive_json()
            waited = time.monotonic() - started
    assert motion["type"] == "motion" and result["type"] == "shot_result"
    assert waited >= motion["duration"] / 4 - 0.05
