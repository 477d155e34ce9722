"""What a `Room` tells the table beyond the rules: the first break's longer clock, the chat
kept for members who connect later, and a match abandoned when everyone left."""

from __future__ import annotations

import pytest

from server.rooms import ActionError, Room
from server.rooms.room import CHAT_KEPT, FIRST_BREAK_FACTOR
from tests.support.games import BREAK, seated, strike


def test_the_rooms_first_break_gets_a_longer_clock_then_the_room_clock():
    room, _ = seated(shot_clock=30.0)
    assert room.clock_limit() == 30.0 * FIRST_BREAK_FACTOR
    strike(room, BREAK)  # Ana's break pockets a ball; she shoots again, no longer a break
    assert room.clock_limit() == 30.0
    empty = Room("r00m1d_waiti", "eight_ball", shot_clock=30.0)
    assert empty.clock_limit() == 30.0  # nobody seated: no match, no break


def test_the_chat_is_kept_for_a_state_sent_to_one_member_only():
    room, _ = seated()
    for k in range(CHAT_KEPT + 5):
        line = room.say(k % 2, f"line {k}", at=1000.0 + k)
        assert (line.seat, line.name, line.text) == (k % 2, ["Ana", "Ben"][k % 2], f"line {k}")
    spectator = room.say(None, "hello", at=2000.0)
    assert spectator.name == "spectator"
    personal = room.state_message(None, [], chat=True)
    assert personal.chat is not None and len(personal.chat) == CHAT_KEPT
    assert personal.chat[0].text == "line 6" and personal.chat[-1].text == "hello"
    assert room.state_message(None, []).chat is None  # broadcasts stay small


def test_an_abandoned_match_is_over_without_a_winner_and_refuses_play():
    room, _ = seated()
    room.abandon()
    assert room.phase == "over" and room.status == "finished"
    info = room.state_message(None, []).room
    assert info.abandoned is True
    assert room.match is not None and room.match.winner is None
    for action in (lambda: room.begin_shot(0), lambda: room.vote_rematch(1)):
        with pytest.raises(ActionError) as refused:
            action()
        assert refused.value.code == "abandoned"
