"""A shot streamed to the room: frames, events, `shot_result`, the next `state`."""

from __future__ import annotations

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
    flat_events,
    flat_frames,
    greet,
    receive_until,
)
from tests.support.rooms import connect, make_client, seated_room

pytestmark = pytest.mark.timeout(120)


def test_break_is_streamed_to_both_players_and_a_spectator(settings):
    # pace 2: a frame message every 50 ms, so a busy test machine does not make the room
    # skip stale frames (a late room does; see the test below)
    with make_client(settings, pace=2.0) as client:
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
    assert [m["type"] for m in stream[-2:]] == ["shot_result", "state"]
    assert stream[0]["type"] == "event" and stream[0]["kind"] == "strike"
    assert stream[0]["speed"] == pytest.approx(9.0)

    messages = [m for m in stream if m["type"] == "frame"]
    assert all(len(m.get("ahead", ())) <= 3 for m in messages)  # 4 frames per message
    assert sum("ahead" in m for m in messages) >= len(messages) - 2
    frames = flat_frames(stream)
    ticks = [f["tick"] for f in frames]
    assert ticks == sorted(set(ticks)) and ticks[:2] == [6, 12]
    assert all(t % 6 == 0 for t in ticks[:-1])  # every 6th tick (a late loop skips some)
    assert frames[-1].get("last") is True and all("last" not in f for f in frames[:-1])
    assert frames[-1]["tick"] == eight_ball_break_ticks()
    for frame in frames:
        for ball_id, x, y, cel in frame["b"]:
            assert 0 <= ball_id <= 15 and 0 <= cel < 16
            assert -100 <= x <= 2640 and -100 <= y <= 1370
    assert len(frames[0]["b"]) == 16
    first_positions = {row[0]: row[1:3] for row in frames[0]["b"]}
    assert first_positions[0][0] > 635  # the cue ball left the head spot along +x

    event_messages = [m for m in stream if m["type"] == "event"]
    events = flat_events(stream)
    assert len(event_messages) < len(events)  # a break's contacts share messages (`also`)
    kinds = {e["kind"] for e in events}
    assert {"strike", "ball", "cushion"} <= kinds and "rest" not in kinds
    assert any(e["kind"] == "ball" and 0 in e["ids"] for e in events)
    event_ticks = [e["tick"] for e in events]
    assert event_ticks == sorted(event_ticks)
    for e in event_messages:  # before the first frame message at or after its tick ...
        later = [f for f in messages if f["tick"] >= e["tick"]]
        assert not later or stream.index(e) < stream.index(later[0])
        # ... with the events of at most one frame message's span (4 frames of 6 ticks)
        assert all(0 <= a["tick"] - e["tick"] <= 25 for a in e.get("also", ()))

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
    assert [e["ids"] for e in events if e["kind"] == "pocket"] == [[EIGHT_BALL_BREAK_BALL]]
    assert len(frames[-1]["b"]) == len(state["balls"]) == 15
    assert sorted(state["balls"]) == sorted(frames[-1]["b"])  # where the stream ended


def test_member_joining_mid_shot_gets_state_and_joins_the_stream(settings):
    with make_client(settings, pace=2.0) as client:
        room_id, ta, _ = seated_room(client)
        with connect(client, room_id, ta) as a:
            greet(a)
            a.send_json(BREAK_MESSAGE)
            for _ in range(1000):
                message = a.receive_json()
                if message["type"] == "frame" and message["tick"] >= 60:
                    break
            with connect(client, room_id) as s:
                welcome, state = greet(s)
                assert state["phase"] == "rolling"
                assert state["shot"]["id"] == 1 and state["shot"]["seat"] == 0
                assert (
                    60 <= state["shot"]["tick"] < state["shot"]["ticks"] == eight_ball_break_ticks()
                )
                assert state["match"]["turn"] == 0  # the match as it was at the strike
                assert state["match"]["balls"][EIGHT_BALL_BREAK_BALL]["on_table"]
                assert 10 <= len(state["balls"]) <= 16
                assert state["seq"] == welcome["seq"]
                rest = receive_until(s, "state")
            seqs = [m["seq"] for m in rest]
            assert seqs[0] == welcome["seq"] + 2  # after our own presence
            assert seqs == list(range(seqs[0], seqs[0] + len(seqs)))
            frames = [m for m in rest if m["type"] == "frame"]
            assert frames and frames[0]["tick"] > state["shot"]["tick"]
            assert frames[-1]["tick"] == state["shot"]["ticks"]
            assert rest[-2]["type"] == "shot_result"


def test_rest_state_is_the_same_over_http_and_websocket(client):
    room_id, ta, _ = seated_room(client)
    with connect(client, room_id, ta) as a:
        greet(a)
        a.send_json(BREAK_MESSAGE)
        final = receive_until(a, "state")[-1]
        http_state = client.get(f"/api/rooms/{room_id}").json()["state"]
    assert http_state["balls"] == final["balls"]
    assert http_state["match"] == final["match"]


def test_a_late_room_skips_stale_frames_but_never_events_or_the_last_frame(settings):
    """The loop stalls mid-shot (an overloaded server): the frames that fell due meanwhile
    are not sent as a burst; the stream stays gapless and ends exactly as planned."""
    import time

    with make_client(settings, pace=1.0) as client:
        room_id, ta, _ = seated_room(client)
        live = client.app.state.registry.get(room_id)
        show = live.room.show
        stalled = []

        def stall_once(timed, frames):
            if timed.frame is not None and not stalled:
                stalled.append(timed.tick)
                time.sleep(1.0)  # blocks the event loop: 120 ticks of frames fall due
            show(timed, frames)

        live.room.show = stall_once
        with connect(client, room_id, ta) as a:
            greet(a)
            a.send_json(BREAK_MESSAGE)
            stream = receive_until(a, "state")
    seqs = [m["seq"] for m in stream]
    assert seqs == list(range(seqs[0], seqs[0] + len(seqs)))
    frames = [m for m in stream if m["type"] == "frame"]
    ticks = [f["tick"] for f in frames]
    per_second = 20 / settings.frames_per_message  # frame messages a second
    assert client.app.state.registry.metrics.frames_skipped >= per_second - 2  # in 1 s
    assert not any(stalled[0] < t < stalled[0] + 96 for t in ticks)  # skipped, not sent late
    assert frames[-1].get("last") is True
    events = flat_events(stream)
    assert len(events) > 20 and events[0]["kind"] == "strike"
