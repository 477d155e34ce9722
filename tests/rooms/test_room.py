"""`Room`, the synchronous state machine behind a table: seats and names, phases, who acts,
shots with a fixed rack, refusals (an `ActionError` that changes nothing), rematch, practice."""

from __future__ import annotations

import json
from collections.abc import Callable

import pytest

from server.codec import encode
from server.engine import Shot, simulate
from server.protocol.outbound import StateMessage
from server.rooms import ActionError, Room
from server.rooms.snapshot import room_to_snapshot
from server.rooms.tokens import hash_token
from tests.support.games import (
    BREAK,
    EIGHT_BALL,
    EIGHT_BALL_BREAK_BALL,
    EIGHT_BALL_PLACE,
    EIGHT_BALL_SCRATCH,
    NINE_BALL,
    NINE_BALL_BREAK,
    SOFT_BREAK,
    eight_ball_break_ticks,
    seated,
    strike,
)


def saved(room: Room) -> str:
    """Everything a room holds (seats, match, shots, votes, the shot in flight), as text."""
    shot = None if room.shot is None else (room.shot.id, room.shot.seat, room.shot.ticks)
    return encode(
        {"room": room_to_snapshot(room, None), "shot": shot, "spectators": room.spectators}
    )


def refused(room: Room, action: Callable[[], object], code: str) -> ActionError:
    """`action` raises `ActionError(code)` and leaves the room exactly as it was."""
    before = saved(room)
    with pytest.raises(ActionError) as caught:
        action()
    assert caught.value.code == code
    assert caught.value.message and str(caught.value) == caught.value.message
    assert saved(room) == before
    return caught.value


# ---- seats and names ---------------------------------------------------------------------


def test_join_gives_the_seats_in_order_and_starts_the_match_when_full() -> None:
    room = Room("r00m1d_abcde", "eight_ball", race_to=3, seed=EIGHT_BALL)
    assert (room.phase, room.status, room.match, room.acting_seat()) == (
        "waiting",
        "waiting",
        None,
        None,
    )
    seat, ana = room.join("  Ana  ")
    assert seat == 0 and room.match is None and room.player_names() == ("Ana",)
    seat, ben = room.join("Ben")
    assert seat == 1 and ana != ben and len(ana) >= 40
    assert room.player_names() == ("Ana", "Ben")
    assert room.match is not None and room.match.players == ("Ana", "Ben")
    assert (room.match.race_to, room.match.seed) == (3, EIGHT_BALL)
    assert (room.phase, room.status, room.acting_seat()) == ("aiming", "playing", 0)
    assert [room.seat_of(ana), room.seat_of(ben), room.seat_of(ana + "x")] == [0, 1, None]
    assert room.seats[0] is not None and room.seats[0].token_hash == hash_token(ana)
    assert ana not in repr(room.seats)  # only hashes are kept
    assert [room.name_of(0), room.name_of(1), room.name_of(None)] == ["Ana", "Ben", "spectator"]


def test_a_third_player_is_refused_and_practice_has_one_seat() -> None:
    room, _ = seated("eight_ball")
    assert "Both seats" in refused(room, lambda: room.join("Cy"), "room_full").message
    practice = Room("practice_id0", "practice")
    assert practice.join("Pia")[0] == 0
    assert "one seat" in refused(practice, lambda: practice.join("Cy"), "room_full").message


@pytest.mark.parametrize(
    "name", ["", "   ", "x" * 25, "tab\there", "new\nline", "\x00", "bell\x07"]
)
def test_bad_names_are_refused(name: str) -> None:
    room = Room("r00m1d_abcde", "eight_ball")
    refused(room, lambda: room.join(name), "bad_name")
    assert room.seats == [None, None]


def test_a_name_of_24_characters_is_fine_and_seats_without_a_player_are_named() -> None:
    room = Room("r00m1d_abcde", "nine_ball")
    room.join("y" * 24)
    assert room.name_of(0) == "y" * 24 and room.name_of(1) == "seat 1"
    assert [p.model_dump() for p in room.players_info()] == [
        {"seat": 0, "name": "y" * 24, "connected": False}
    ]


def test_unknown_game_and_practice_settings() -> None:
    with pytest.raises(ValueError):
        Room("r00m1d_abcde", "four_ball")
    practice = Room("practice_id0", "practice", race_to=5, shot_clock=30.0)
    assert (practice.seats, practice.race_to, practice.shot_clock) == ([None], 1, 0.0)
    practice.join("Pia")
    assert practice.phase == "aiming" and practice.status == "playing"


# ---- phases, shots and who acts ----------------------------------------------------------


def test_a_shot_goes_from_aiming_to_rolling_and_back_with_the_judged_outcome() -> None:
    room, _ = seated("eight_ball", EIGHT_BALL)
    assert room.match is not None
    rack = room.resting_balls()
    assert len(rack) == 16 and rack[0][:3] == (0, 635, 635)  # the cue ball on the head spot

    shot_id, before = room.begin_shot(0)
    assert (shot_id, room.shots_played, room.phase, room.acting_seat()) == (1, 1, "rolling", None)
    assert room.shot is not None and (room.shot.id, room.shot.seat) == (1, 0)
    assert room.shot.before == rack and room.shot.balls == rack  # nothing streamed yet
    assert room.shot.match_before == room.match.public_state()
    assert before is not room.match.game.balls  # the caller simulates a copy

    result = simulate(room.match.game.table, before, BREAK)
    outcome = room.apply_shot(result)
    assert outcome.pocketed == (EIGHT_BALL_BREAK_BALL,) and outcome.continues
    assert room.phase == "rolling" and room.shot.outcome == outcome
    assert room.shot.ticks == eight_ball_break_ticks()
    state = room.state_message(None, [])
    assert state.phase == "rolling" and state.shot is not None
    assert (state.shot.id, state.shot.seat, state.shot.ticks) == (1, 0, eight_ball_break_ticks())
    assert state.match is not None and state.match["turn"] == 0  # as at the strike

    room.end_shot()
    assert room.shot is None and room.phase == "aiming" and room.acting_seat() == 0
    assert EIGHT_BALL_BREAK_BALL not in [row[0] for row in room.resting_balls()]
    assert len(room.resting_balls()) == 15


def test_the_state_message_is_valid_in_every_phase() -> None:
    room = Room("r00m1d_abcde", "eight_ball", seed=EIGHT_BALL, created_at=12.5)
    room.join("Ana")
    waiting = room.state_message(None, [])
    assert (waiting.phase, waiting.match, waiting.balls) == ("waiting", None, [])
    assert waiting.table["length"] == pytest.approx(2.54)
    room.join("Ben")
    aiming = room.state_message(None, [])
    assert aiming.phase == "aiming" and aiming.room.status == "playing"
    assert json.loads(room.table_json()) == aiming.table
    for state in (waiting, aiming):
        StateMessage.model_validate(state.model_dump())
    assert room.summary() | {"created_at": 0} == {
        "room_id": "r00m1d_abcde",
        "game": "eight_ball",
        "race_to": 1,
        "shot_clock": 60.0,
        "seats": 2,
        "status": "playing",
        "players": ["Ana", "Ben"],
        "spectators": 0,
        "score": [0, 0],
        "created_at": 0,
    }
    assert room.summary()["created_at"] == 12.5


def test_after_a_scratch_the_other_seat_acts_with_ball_in_hand() -> None:
    room, _ = seated("eight_ball", EIGHT_BALL)
    strike(room, BREAK)
    strike(room, EIGHT_BALL_SCRATCH)
    assert room.match is not None and room.acting_seat() == 1
    assert not room.match.game.balls.on_table[0]
    refused(room, lambda: room.begin_shot(1), "cue_ball_off_table")
    refused(room, lambda: room.place_cue(0, *EIGHT_BALL_PLACE), "not_your_turn")
    room.place_cue(1, *EIGHT_BALL_PLACE)
    x, y = EIGHT_BALL_PLACE
    assert room.resting_balls()[0][:3] == (0, round(1000 * x), round(1000 * y))


def test_a_pending_decision_names_the_acting_seat_and_blocks_shooting() -> None:
    room, _ = seated("eight_ball", EIGHT_BALL)
    strike(room, SOFT_BREAK)  # an illegal break: Ben chooses
    assert room.acting_seat() == 1
    refused(room, lambda: room.begin_shot(1), "decision_pending")
    refused(room, lambda: room.decide(0, "accept"), "not_your_turn")
    refused(room, lambda: room.decide(1, "maybe"), "bad_option")
    room.decide(1, "accept")
    assert room.match is not None and room.match.game.decision is None
    assert room.acting_seat() == 1
    refused(room, lambda: room.decide(1, "accept"), "no_decision")


def test_push_out_and_pocket_calls_follow_the_rules() -> None:
    nine, _ = seated("nine_ball", NINE_BALL)
    refused(nine, lambda: nine.push_out(0), "push_out_not_allowed")  # not on the break
    strike(nine, NINE_BALL_BREAK)  # a scratch: Ben may push out
    nine.push_out(1)
    assert nine.match is not None and nine.match.public_state()["push_out_declared"]
    eight, _ = seated("eight_ball", EIGHT_BALL)
    refused(eight, lambda: eight.call_pocket(0, 2), "call_not_needed")


# ---- refusals --------------------------------------------------------------------------


def test_refusals_raise_with_their_code_and_change_nothing() -> None:
    waiting = Room("r00m1d_abcde", "eight_ball", seed=EIGHT_BALL)
    waiting.join("Ana")
    refused(waiting, lambda: waiting.begin_shot(0), "not_started")
    refused(waiting, lambda: waiting.check_aim(0), "not_started")
    refused(waiting, lambda: waiting.vote_rematch(0), "match_not_over")

    room, _ = seated("eight_ball", EIGHT_BALL)
    for action, code in [
        (lambda: room.begin_shot(None), "spectator"),
        (lambda: room.place_cue(None, 0.4, 0.5), "spectator"),
        (lambda: room.concede(None), "spectator"),
        (lambda: room.vote_rematch(None), "spectator"),
        (lambda: room.begin_shot(1), "not_your_turn"),
        (lambda: room.check_aim(1), "not_your_turn"),
        (lambda: room.place_cue(1, 0.4, 0.5), "not_your_turn"),
        (lambda: room.place_cue(0, 2.0, 0.5), "illegal_placement"),  # past the head string
        (lambda: room.rerack(0), "not_practice"),
        (lambda: room.decide(0, "accept"), "no_decision"),
        (lambda: room.vote_rematch(0), "match_not_over"),
    ]:
        refused(room, action, code)
    room.check_aim(0)  # the breaker may aim

    room.begin_shot(0)  # while the balls roll nobody may act
    for action in (
        lambda: room.begin_shot(0),
        lambda: room.concede(1),
        lambda: room.check_aim(0),
        lambda: room.timeout(0),
    ):
        refused(room, action, "balls_moving")


def test_a_finished_match_refuses_play() -> None:
    room, _ = seated("eight_ball", EIGHT_BALL)
    outcome = room.concede(1)
    assert outcome.winner == 0 and outcome.frame_over
    assert room.phase == "over" and room.status == "finished" and room.acting_seat() is None
    for action in (
        lambda: room.begin_shot(0),
        lambda: room.concede(0),
        lambda: room.place_cue(0, 0.4, 0.5),
        lambda: room.timeout(0),
    ):
        refused(room, action, "match_over")


# ---- the match goes on: timeouts, forfeits, next games, rematch -------------------------


def test_a_timeout_passes_the_turn_and_a_forfeit_loses_the_frame() -> None:
    room, _ = seated("eight_ball", EIGHT_BALL, race_to=2)
    timeout = room.timeout(0)
    assert [f.code for f in timeout.fouls] == ["shot_clock"] and room.acting_seat() == 1
    forfeit = room.forfeit(1, "Ben left the table and did not come back.")
    assert forfeit.winner == 0 and forfeit.frame_over
    assert room.match is not None and room.match.score == [1, 0] and not room.match.over
    assert room.match.game.over and room.phase == "aiming"
    room.after_outcome()  # the next frame is racked; Ben breaks it
    assert not room.match.game.over and room.acting_seat() == 1
    assert room.match.games_played == 1 and room.match.score == [1, 0]


def test_rematch_needs_both_votes_and_the_other_seat_breaks() -> None:
    room, _ = seated("eight_ball", EIGHT_BALL)
    room.concede(0)
    assert room.vote_rematch(0) is False and room.rematch_votes == {0}
    assert room.room_info().rematch == [0]
    assert room.vote_rematch(0) is False and room.rematch_votes == {0}  # counted once
    assert room.vote_rematch(1) is True
    assert room.rematch_votes == set() and room.phase == "aiming"
    assert room.match is not None and room.match.score == [0, 0]
    assert room.acting_seat() == 1 and room.match.seed == EIGHT_BALL + 1


# ---- practice -----------------------------------------------------------------------------


def test_practice_has_ball_in_hand_at_will_and_reracks() -> None:
    room, _ = seated("practice", EIGHT_BALL)
    assert room.acting_seat() == 0
    room.place_cue(0, 1.0, 0.3)  # anywhere, before any shot
    assert room.resting_balls()[0][:3] == (0, 1000, 300)
    outcome = strike(room, Shot(0.5, 3.0))
    assert outcome.fouls == () and outcome.continues and outcome.ball_in_hand == "anywhere"
    room.place_cue(0, 2.2, 0.3)  # and after it, past the head string too
    room.check_aim(0)
    refused(room, lambda: room.concede(0), "not_allowed")
    room.rerack(0)
    assert room.resting_balls()[0][:3] == (0, 635, 635) and len(room.resting_balls()) == 16
    assert room.shots_played == 1 and room.phase == "aiming"


def test_a_snooker_practice_table_has_one_seat_and_the_snooker_table() -> None:
    practice = Room("practice_id1", "snooker_practice", race_to=3, shot_clock=30.0)
    assert (practice.seats, practice.race_to, practice.shot_clock) == ([None], 1, 0.0)
    practice.join("Pia")
    assert practice.phase == "aiming" and practice.match is not None
    assert practice.match.game.table.style == "snooker"


def test_three_cushion_rooms_have_the_carom_table_and_strike_the_strikers_ball() -> None:
    room = Room("carom_id0001", "three_cushion", race_to=1, shot_clock=30.0)
    room.join("Ana")
    room.join("Ben")
    assert room.match is not None and room.match.game.table.style == "carom"
    assert room.cue_ball() == 0
    room.match.game.turn = 1
    assert room.cue_ball() == 1
    practice = Room("practice_id2", "three_cushion_practice", race_to=3, shot_clock=30.0)
    assert practice.seats == [None]
    practice.join("Pia")
    assert practice.match is not None and practice.cue_ball() == 0
