"""A room saved to JSON comes back with its seats (token hashes only), match and pending shot;
rooms saved in the first stored form (before `Game` and `Match` went through the codec)
still load."""

from __future__ import annotations

import json
from pathlib import Path

from server.codec import encode
from server.engine import Shot, simulate
from server.rooms.room import Room
from server.rooms.snapshot import pending_shot, room_from_snapshot, room_to_snapshot
from tests.support.games import (
    BREAK,
    EIGHT_BALL,
    EIGHT_BALL_PLACE,
    EIGHT_BALL_SCRATCH,
    strike,
)

# Two snapshots of the same 8-ball room (seed 9, race to 3, match record 12), written by the
# server of commit 8e9ab8c, the last before `Game` and `Match` were stored through the
# codec: its `table` a list, its `groups` pairs, its keys in another order. Ana's and Ben's
# tokens were "ana-token" and "ben-token". `v1_pending_shot`: the break (the 7 down), Ana's
# scratch, Ben's cue ball placed at (0.4, 0.3) and his shot (-0.9 rad, 5.5 m/s) struck
# (shot 3, pending); `v1_at_rest`: after that shot (the 11 down, Ben has the stripes).
SNAPSHOTS = Path(__file__).parent / "snapshots"
PENDING = Shot(-0.9, 5.5)  # Ben's shot in `v1_pending_shot`


def old_snapshot(name: str) -> dict:
    return json.loads((SNAPSHOTS / f"{name}.json").read_text())


def played_room() -> tuple[Room, list[str]]:
    """8-ball (`games.EIGHT_BALL`), race to 3: the break, then Ana's scratch: Ben has ball
    in hand."""
    room = Room(
        "r00m1d_abcde",
        "eight_ball",
        race_to=3,
        shot_clock=30.0,
        seed=EIGHT_BALL,
        created_at=1767000000.25,
    )
    tokens = [room.join("Ana")[1], room.join("Ben")[1]]
    strike(room, BREAK)
    strike(room, EIGHT_BALL_SCRATCH)
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
    assert back.shots_by_seat == room.shots_by_seat == [2, 0]  # Ben has not played yet
    assert back.resting_balls() == room.resting_balls()
    assert 0 not in [row[0] for row in back.resting_balls()]  # the cue ball is in hand
    assert back.match.game.ball_in_hand == "anywhere" and back.acting_seat() == 1
    assert [back.seat_of(t) for t in tokens] == [0, 1]
    assert back.seat_of("not-a-token") is None
    assert all(s is not None and not s.connected for s in back.seats)


def test_a_pending_shot_is_saved_with_the_table_before_it_and_replays_the_same() -> None:
    room, _ = played_room()
    assert room.match is not None
    room.place_cue(1, *EIGHT_BALL_PLACE)
    before_state = room.match.to_dict()
    shot = Shot(1.0, 5.0, (0.1, 0.1))
    shot_id, before = room.begin_shot(1)
    text = encode(room_to_snapshot(room, 5, pending_shot(shot_id, 1, shot)))
    live_result = simulate(room.match.game.table, before, shot)
    room.apply_shot(live_result)  # the server died after this, mid-stream

    saved = room_from_snapshot(json.loads(text))
    back, pending = saved.room, saved.pending
    assert pending == (1, shot) and saved.pending_id == shot_id == 3
    assert back.match is not None and back.match.to_dict() == before_state
    assert back.phase == "aiming" and back.shots_played == 2
    assert back.shots_by_seat == [2, 0]  # as before the pending shot was struck
    replay_seat, replay = pending
    again_id, again_before = back.begin_shot(replay_seat)
    assert again_id == shot_id
    again = simulate(back.match.game.table, again_before, replay)
    assert again.frames.positions.tobytes() == live_result.frames.positions.tobytes()
    back.apply_shot(again)
    assert back.match.to_dict() == room.match.to_dict()
    assert back.shots_by_seat == room.shots_by_seat == [2, 1]


def test_a_waiting_room_round_trips() -> None:
    room = Room("waiting_room", "nine_ball", created_at=1.5)
    room.join("Ana")
    saved = room_from_snapshot(json.loads(encode(room_to_snapshot(room, None))))
    back = saved.room
    assert (back.match, saved.match_id, saved.pending) == (None, None, None)
    assert back.summary() == room.summary() and back.seats[1] is None


def test_a_room_saved_at_rest_in_the_first_form_loads() -> None:
    data = old_snapshot("v1_at_rest")
    assert set(data) == {
        "version",
        "room_id",
        "game",
        "race_to",
        "shot_clock",
        "seed",
        "created_at",
        "seats",
        "match",
        "match_id",
        "shots_played",
        "rematch_votes",
        "pending",
    }
    saved = room_from_snapshot(data)
    room = saved.room
    assert (saved.match_id, saved.pending, saved.pending_id) == (12, None, None)
    assert (room.room_id, room.game, room.race_to, room.shot_clock, room.seed) == (
        "old_format_1",
        "eight_ball",
        3,
        30.0,
        9,
    )
    assert (room.created_at, room.shots_played, room.rematch_votes) == (1767000000.25, 3, set())
    assert [room.seat_of("ana-token"), room.seat_of("ben-token")] == [0, 1]
    assert room.player_names() == ("Ana", "Ben")
    assert room.phase == "aiming" and room.acting_seat() == 1
    assert room.match is not None and room.match.score == [0, 0]
    state = room.match.public_state()
    assert state["groups"] == ["solids", "stripes"] and state["ball_in_hand"] is None
    assert state["balls_left"] == [[1, 2, 3, 4, 5, 6], [9, 10, 12, 13, 14, 15]]
    assert room.match.game.table.length == 2.54
    on_table = [row[0] for row in room.resting_balls()]
    assert 7 not in on_table and 11 not in on_table and len(on_table) == 14
    cue = room.match.game.balls.positions[0].tolist()
    assert cue == data["match"]["game"]["balls"]["positions"][0]  # floats exactly as stored
    # and it is saved again in the current form, which loads to the same room
    again = room_from_snapshot(json.loads(encode(room_to_snapshot(room, 12)))).room
    assert again.match is not None and again.match.to_dict() == room.match.to_dict()
    # saved before shots were counted per seat: each seat counted as having played (the
    # rule it was saved under: a ranked match with a shot played is rated)
    assert room.shots_by_seat == again.shots_by_seat == [3, 3]


def test_a_room_saved_mid_shot_in_the_first_form_loads_with_its_pending_shot() -> None:
    saved = room_from_snapshot(old_snapshot("v1_pending_shot"))
    room = saved.room
    assert (saved.match_id, saved.pending, saved.pending_id) == (12, (1, PENDING), 3)
    assert room.shots_played == 2 and room.acting_seat() == 1
    assert room.match is not None and room.match.public_state()["groups"] is None
    assert room.match.game.ball_in_hand == "anywhere"  # Ana had scratched
    assert room.resting_balls()[0][:3] == (0, 400, 300)  # where Ben put the cue ball
    assert [room.seat_of("ana-token"), room.seat_of("ben-token")] == [0, 1]
    # the restart strikes it again from here: the same shot id, judged for Ben
    seat, shot = saved.pending
    shot_id, before = room.begin_shot(seat)
    assert shot_id == 3 and before.positions.tolist() == room.match.game.balls.positions.tolist()
    outcome = room.apply_shot(simulate(room.match.game.table, before, shot))
    room.end_shot()
    assert outcome.shooter == 1 and room.shots_played == 3
