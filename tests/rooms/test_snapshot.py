"""A room saved to JSON comes back with its seats (token hashes only), match and pending shot."""

from __future__ import annotations

import json

from server.engine import Shot, simulate
from server.rooms.room import Room
from server.codec import encode
from server.rooms.snapshot import pending_shot, room_from_snapshot, room_to_snapshot


def played_room() -> tuple[Room, list[str]]:
    room = Room("r00m1d_abcde", "eight_ball", race_to=3, shot_clock=30.0, seed=42,
                created_at=1767000000.25)
    tokens = [room.join("Ana")[1], room.join("Ben")[1]]
    for shot in (Shot(0.0, 9.0), Shot(2.0, 3.0)):
        assert room.match is not None
        seat = room.match.game.turn
        if not room.match.game.balls.on_table[0]:
            room.place_cue(seat, 0.5, 0.6)
        shot_id, before = room.begin_shot(seat, shot)
        room.apply_shot(simulate(room.match.game.table, before, shot))
        room.end_shot()
    return room, tokens


def test_room_round_trip_keeps_everything_but_tokens_in_clear() -> None:
    room, tokens = played_room()
    text = encode(room_to_snapshot(room, match_id=5))
    for token in tokens:
        assert token not in text
    saved = room_from_snapshot(json.loads(text))
    back, match_id, pending = saved.room, saved.match_id, saved.pending
    assert (match_id, pending) == (5, None)
    assert back.summary() == room.summary()
    assert back.match is not None and room.match is not None
    assert back.match.to_dict() == room.match.to_dict()
    assert back.shots_played == room.shots_played == 2
    assert back.resting_balls() == room.resting_balls()
    assert [back.seat_of(t) for t in tokens] == [0, 1]
    assert back.seat_of("not-a-token") is None
    assert all(s is not None and not s.connected for s in back.seats)


def test_a_pending_shot_is_saved_with_the_table_before_it_and_replays_the_same() -> None:
    room, _ = played_room()
    assert room.match is not None
    seat = room.match.game.turn
    if not room.match.game.balls.on_table[0]:
        room.place_cue(seat, 0.5, 0.6)
    before_state = room.match.to_dict()
    shot = Shot(1.0, 5.0, (0.1, 0.1))
    shot_id, before = room.begin_shot(seat, shot)
    text = encode(room_to_snapshot(room, 5, pending_shot(shot_id, seat, shot)))
    live_result = simulate(room.match.game.table, before, shot)
    room.apply_shot(live_result)  # the server died after this, mid-stream

    saved = room_from_snapshot(json.loads(text))
    back, pending = saved.room, saved.pending
    assert pending == (seat, shot) and saved.pending_id == shot_id
    assert back.match is not None and back.match.to_dict() == before_state
    assert back.phase == "aiming"
    replay_seat, replay = pending
    again_id, again_before = back.begin_shot(replay_seat, replay)
    assert again_id == shot_id
    again = simulate(back.match.game.table, again_before, replay)
    assert again.frames.positions.tobytes() == live_result.frames.positions.tobytes()
    back.apply_shot(again)
    assert back.match.to_dict() == room.match.to_dict()


def test_a_waiting_room_round_trips() -> None:
    room = Room("waiting_room", "nine_ball", created_at=1.5)
    room.join("Ana")
    saved = room_from_snapshot(json.loads(encode(room_to_snapshot(room, None))))
    back = saved.room
    assert (back.match, saved.match_id, saved.pending) == (None, None, None)
    assert back.summary() == room.summary() and back.seats[1] is None
