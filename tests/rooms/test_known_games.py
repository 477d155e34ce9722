"""The fixed games of `tests.support.games` do what their docstrings say.

The server, recovery and browser tests play these racks and assert their outcomes; if
physics or rules change one of them, this says which game changed and how (then pick new
seeds and shots that do what the docstrings say, and update the constants there).
"""

from __future__ import annotations

from tests.support.games import (
    BREAK,
    EIGHT_BALL,
    EIGHT_BALL_BREAK_BALL,
    EIGHT_BALL_BREAK_SAYS,
    EIGHT_BALL_GROUP_BALL,
    EIGHT_BALL_GROUP_SHOT,
    EIGHT_BALL_PLACE,
    EIGHT_BALL_SCRATCH,
    NINE_BALL,
    NINE_BALL_BREAK,
    NINE_BALL_FOUL,
    NINE_BALL_FOUL_BALL,
    NINE_BALL_PLACE,
    SOFT_BREAK,
    seated,
    strike,
)


def test_eight_ball_break_pockets_one_ball_and_the_breaker_shoots_again() -> None:
    room, _ = seated("eight_ball", EIGHT_BALL)
    assert room.match is not None
    outcome = strike(room, BREAK)
    assert (outcome.pocketed, outcome.fouls) == ((EIGHT_BALL_BREAK_BALL,), ())
    assert outcome.continues and outcome.message == EIGHT_BALL_BREAK_SAYS
    assert room.match.game.groups is None and room.acting_seat() == 0


def test_eight_ball_then_a_scratch_then_ben_takes_a_group() -> None:
    room, _ = seated("eight_ball", EIGHT_BALL)
    strike(room, BREAK)
    scratch = strike(room, EIGHT_BALL_SCRATCH)
    assert scratch.pocketed == (0,)
    assert [f.code for f in scratch.fouls] == ["no_contact", "scratch"]
    assert (scratch.next_turn, scratch.ball_in_hand) == (1, "anywhere")
    group = strike(room, EIGHT_BALL_GROUP_SHOT, place=EIGHT_BALL_PLACE)
    assert (group.shooter, group.pocketed, group.fouls) == (1, (EIGHT_BALL_GROUP_BALL,), ())
    assert group.continues and group.next_turn == 1
    bens, anas = ("stripes", "solids") if EIGHT_BALL_GROUP_BALL > 8 else ("solids", "stripes")
    assert group.message == (
        f"Ben pocketed the {EIGHT_BALL_GROUP_BALL}. Ben takes the {bens}; Ana has the {anas}. "
        "Ben shoots again."
    )


def test_eight_ball_soft_break_is_illegal_and_ben_decides() -> None:
    room, _ = seated("eight_ball", EIGHT_BALL)
    outcome = strike(room, SOFT_BREAK)
    assert [f.code for f in outcome.fouls] == ["illegal_break"] and outcome.pocketed == ()
    assert outcome.decision is not None and outcome.decision.seat == 1
    assert outcome.decision.options == ("accept", "rerack", "rerack_opponent_breaks")


def test_nine_ball_break_scratches_then_a_foul_pockets_a_ball_that_stays_down() -> None:
    room, _ = seated("nine_ball", NINE_BALL)
    scratch = strike(room, NINE_BALL_BREAK)
    assert (scratch.pocketed, [f.code for f in scratch.fouls]) == ((0,), ["scratch"])
    assert (scratch.next_turn, scratch.ball_in_hand) == (1, "anywhere")
    assert room.match is not None and room.match.game.push_out_available
    foul = strike(room, NINE_BALL_FOUL, place=NINE_BALL_PLACE)
    assert (foul.shooter, foul.pocketed, foul.spotted) == (1, (NINE_BALL_FOUL_BALL,), ())
    assert [f.code for f in foul.fouls] == ["wrong_ball_first"]
    assert (foul.next_turn, foul.ball_in_hand, foul.frame_over) == (0, "anywhere", False)
    assert NINE_BALL_FOUL_BALL not in room.match.game.balls.on_table_ids()
