"""WPA 8-ball, one test per rule."""

from __future__ import annotations

import pytest

from server.engine import Shot, simulate
from server.rules import ANYWHERE, BEHIND_HEAD_STRING, Game, IllegalActionError, RuleOptions

from .helpers import TABLE, arrange, crafted, hit, pot, rail, straight_in


def legal_break_pocketing(game: Game, ball: int = 1) -> None:
    """Ana breaks and pockets `ball`: a legal break, Ana shoots again on an open table."""
    game.apply(0, crafted(game.balls, hit(0, ball), rail(ball), pot(ball, 2)))


def solids_for_ana(game: Game) -> None:
    legal_break_pocketing(game, 1)
    game.apply(0, crafted(game.balls, hit(0, 2), pot(2, 3)))
    assert game.groups == {0: "solids", 1: "stripes"}


# --- the break -------------------------------------------------------------------------
def test_break_is_taken_from_behind_the_head_string(eight: Game) -> None:
    assert eight.ball_in_hand == BEHIND_HEAD_STRING
    assert eight.can_place_cue(TABLE.head_string - 0.1, 0.4)
    assert not eight.can_place_cue(TABLE.head_string + 0.01, 0.4)
    with pytest.raises(IllegalActionError) as err:
        eight.place_cue(0, TABLE.head_string + 0.3, 0.4)
    assert err.value.code == "illegal_placement"
    eight.place_cue(0, 0.3, 0.5)
    assert eight.balls.position_of(0) == (0.3, 0.5)


def test_real_break_from_a_placed_cue_ball_is_judged(eight: Game) -> None:
    eight.place_cue(0, TABLE.head_string, TABLE.width / 2 + 0.01)
    result = simulate(TABLE, eight.balls, Shot(0.0, 10.0))
    outcome = eight.apply(0, result)
    assert not eight.breaking
    assert eight.groups is None  # the table is open after the break
    assert set(outcome.pocketed) == set(result.pocketed())
    assert "break" in outcome.message.lower() or outcome.fouls


def test_legal_break_by_pocketing_a_ball_keeps_the_breaker_at_the_table(eight: Game) -> None:
    outcome = eight.apply(0, crafted(eight.balls, hit(0, 1), pot(1, 2)))
    assert outcome.fouls == () and outcome.continues and outcome.next_turn == 0
    assert eight.groups is None  # a ball on the break does not choose a group
    assert outcome.message == (
        "Ana pocketed the 1. Legal break. The table is open. Ana shoots again."
    )


def test_legal_break_with_four_balls_to_a_rail_passes_the_turn(eight: Game) -> None:
    events = [hit(0, 1)] + [rail(b) for b in (2, 3, 9, 10)]
    outcome = eight.apply(0, crafted(eight.balls, *events))
    assert outcome.fouls == () and not outcome.continues
    assert eight.turn == 1 and eight.decision is None and eight.ball_in_hand is None


def test_illegal_break_lets_the_opponent_accept_or_rerack(eight: Game) -> None:
    events = [hit(0, 1), rail(2), rail(3), rail(3), rail(9), rail(0)]
    outcome = eight.apply(0, crafted(eight.balls, *events))
    assert [f.code for f in outcome.fouls] == ["illegal_break"]
    assert "only 3 object balls" in outcome.fouls[0].message
    assert eight.decision is not None and eight.decision.seat == 1
    assert eight.decision.options == ("accept", "rerack", "rerack_opponent_breaks")
    with pytest.raises(IllegalActionError) as err:
        eight.check_shot(1)
    assert err.value.code == "decision_pending"
    eight.decide(1, "accept")
    assert eight.turn == 1 and eight.ball_in_hand is None and not eight.breaking
    eight.check_shot(1)


@pytest.mark.parametrize(("option", "breaker"), [("rerack", 1), ("rerack_opponent_breaks", 0)])
def test_illegal_break_rerack_options(eight: Game, option: str, breaker: int) -> None:
    eight.apply(0, crafted(eight.balls, hit(0, 1)))
    eight.decide(1, option)
    assert eight.breaking and eight.turn == breaker and eight.breaker == breaker
    assert eight.ball_in_hand == BEHIND_HEAD_STRING
    assert len(eight.balls.on_table_ids()) == 16


def test_break_scratch_gives_ball_in_hand_anywhere(eight: Game) -> None:
    outcome = eight.apply(0, crafted(eight.balls, hit(0, 1), pot(3, 0), pot(0, 5)))
    assert [f.code for f in outcome.fouls] == ["scratch"]
    assert outcome.next_turn == 1 and outcome.ball_in_hand == ANYWHERE
    assert outcome.message == (
        "Foul: scratch. Ana pocketed the 3. Legal break. The table is open. Ball in hand for Bob."
    )
    assert 3 not in eight.balls.on_table_ids()  # balls pocketed on the break stay down
    assert eight.groups is None
    with pytest.raises(IllegalActionError) as err:
        eight.check_shot(1)
    assert err.value.code == "cue_ball_off_table"
    eight.place_cue(1, 2.0, 0.2)  # past the head string: anywhere
    eight.check_shot(1)


def test_break_scratch_behind_head_string_is_a_room_option() -> None:
    game = Game.new(
        "eight_ball",
        ("Ana", "Bob"),
        table=TABLE,
        options=RuleOptions(break_scratch_behind_head_string=True),
    )
    outcome = game.apply(0, crafted(game.balls, hit(0, 1), pot(3, 0), pot(0, 5)))
    assert outcome.ball_in_hand == BEHIND_HEAD_STRING
    assert outcome.message.endswith("Ball in hand behind the head string for Bob.")
    assert not game.can_place_cue(2.0, 0.2)
    assert game.can_place_cue(0.4, 0.2)


def test_eight_on_the_break_is_spotted_at_the_breakers_choice(eight: Game) -> None:
    outcome = eight.apply(0, crafted(eight.balls, hit(0, 1), pot(8, 2)))
    assert not outcome.frame_over and outcome.fouls == ()
    assert eight.decision is not None and eight.decision.seat == 0
    assert eight.decision.options == ("spot", "rerack")
    eight.decide(0, "spot")
    assert 8 in eight.balls.on_table_ids()
    # the foot spot is taken by the rack, so the 8 sits behind it on the long string
    x, y = eight.balls.position_of(8)
    assert y == TABLE.width / 2 and x > TABLE.foot_spot[0]
    assert eight.turn == 0 and eight.ball_in_hand is None and eight.groups is None


def test_eight_on_the_break_rerack(eight: Game) -> None:
    eight.apply(0, crafted(eight.balls, hit(0, 1), pot(8, 2)))
    eight.decide(0, "rerack")
    assert eight.breaking and eight.turn == 0 and len(eight.balls.on_table_ids()) == 16


def test_eight_and_scratch_on_the_break_lets_the_opponent_choose(eight: Game) -> None:
    outcome = eight.apply(0, crafted(eight.balls, hit(0, 1), pot(8, 2), pot(0, 0)))
    assert [f.code for f in outcome.fouls] == ["scratch"] and not outcome.frame_over
    assert eight.decision is not None and eight.decision.seat == 1 and eight.turn == 1
    eight.decide(1, "spot")
    assert eight.turn == 1 and eight.ball_in_hand == ANYWHERE


# --- open table and groups -------------------------------------------------------------
def test_open_table_any_solid_or_stripe_may_be_hit_first(eight: Game) -> None:
    legal_break_pocketing(eight)
    outcome = eight.apply(0, crafted(eight.balls, hit(0, 3), hit(3, 12), pot(12, 4)))
    assert outcome.fouls == () and outcome.continues
    assert eight.groups == {0: "stripes", 1: "solids"}  # the ball pocketed decides


def test_open_table_eight_first_is_a_foul(eight: Game) -> None:
    legal_break_pocketing(eight)
    outcome = eight.apply(0, crafted(eight.balls, hit(0, 8), rail(8)))
    assert [f.code for f in outcome.fouls] == ["wrong_ball_first"]
    assert outcome.ball_in_hand == ANYWHERE and outcome.next_turn == 1


def test_groups_are_decided_by_the_first_legal_pot_after_the_break(eight: Game) -> None:
    legal_break_pocketing(eight)
    outcome = eight.apply(0, crafted(eight.balls, hit(0, 2), pot(2, 3), pot(10, 1)))
    assert eight.groups == {0: "solids", 1: "stripes"}
    assert "Ana takes the solids; Bob has the stripes." in outcome.message
    assert eight.public_state()["groups"] == ["solids", "stripes"]


def test_a_foul_does_not_decide_groups(eight: Game) -> None:
    legal_break_pocketing(eight)
    eight.apply(0, crafted(eight.balls, hit(0, 2), pot(2, 3), pot(0, 0)))
    assert eight.groups is None and eight.turn == 1


# --- fouls -----------------------------------------------------------------------------
def test_own_group_must_be_hit_first(eight: Game) -> None:
    solids_for_ana(eight)
    outcome = eight.apply(0, crafted(eight.balls, hit(0, 9), hit(9, 3), pot(3, 0)))
    assert [f.code for f in outcome.fouls] == ["wrong_ball_first"]
    assert outcome.fouls[0].message == (
        "Ana hit the 9 first; the first ball hit must be one of the solids."
    )
    assert outcome.next_turn == 1 and outcome.ball_in_hand == ANYWHERE
    assert 3 not in eight.balls.on_table_ids()  # pocketed balls stay down


def test_a_rail_or_a_pocket_is_needed_after_contact(eight: Game) -> None:
    solids_for_ana(eight)
    outcome = eight.apply(0, crafted(eight.balls, rail(0), hit(0, 3)))
    assert [f.code for f in outcome.fouls] == ["no_rail"]  # the rail came before contact
    assert outcome.message == "Foul: no rail after contact. Ball in hand for Bob."


def test_rail_after_contact_is_legal(eight: Game) -> None:
    solids_for_ana(eight)
    outcome = eight.apply(0, crafted(eight.balls, hit(0, 3), rail(0)))
    assert outcome.fouls == () and outcome.next_turn == 1
    assert outcome.message == "No ball pocketed. Bob to shoot."


def test_real_scratch_without_contact(eight: Game) -> None:
    solids_for_ana(eight)
    placement, shot = straight_in(3, pocket=0)
    arrange(eight, {0: placement[3]})  # the cue ball where the 3 would be: straight in
    outcome = eight.apply(0, simulate(TABLE, eight.balls, shot))
    assert {f.code for f in outcome.fouls} == {"no_contact", "scratch"}
    assert outcome.next_turn == 1 and outcome.ball_in_hand == ANYWHERE
    assert 0 in outcome.pocketed


def test_no_contact_is_a_foul(eight: Game) -> None:
    solids_for_ana(eight)
    outcome = eight.apply(0, crafted(eight.balls, rail(0), rail(0, 2)))
    assert [f.code for f in outcome.fouls] == ["no_contact"]


def test_pocketing_only_the_opponents_ball_ends_the_turn(eight: Game) -> None:
    solids_for_ana(eight)
    outcome = eight.apply(0, crafted(eight.balls, hit(0, 3), hit(3, 11), pot(11, 1)))
    assert outcome.fouls == () and not outcome.continues and eight.turn == 1
    assert 11 not in eight.balls.on_table_ids()


def test_real_pot_of_own_ball_continues(eight: Game) -> None:
    solids_for_ana(eight)
    placement, shot = straight_in(3, pocket=0)
    arrange(eight, placement)
    outcome = eight.apply(0, simulate(TABLE, eight.balls, shot))
    assert outcome.pocketed == (3,) and outcome.continues and eight.turn == 0


def test_three_fouls_in_a_row_do_not_lose_in_eight_ball(eight: Game) -> None:
    solids_for_ana(eight)
    for _ in range(3):
        seat = eight.turn
        eight.apply(seat, crafted(eight.balls, rail(0)))
        eight.apply(1 - seat, crafted(eight.balls, hit(0, 3 if seat else 9), rail(0)))
    assert not eight.over


# --- the 8 -----------------------------------------------------------------------------
def clear_solids(game: Game) -> None:
    solids_for_ana(game)
    events = [hit(0, 3)] + [pot(b, 1) for b in (3, 4, 5, 6, 7)]
    game.apply(0, crafted(game.balls, *events))
    assert game.turn == 0 and game.requires_call


def test_the_eight_must_be_called_once_the_group_is_cleared(eight: Game) -> None:
    solids_for_ana(eight)
    assert not eight.requires_call
    with pytest.raises(IllegalActionError) as err:
        eight.call_pocket(0, 1)
    assert err.value.code == "call_not_needed"
    events = [hit(0, 3)] + [pot(b, 1) for b in (3, 4, 5, 6, 7)]
    eight.apply(0, crafted(eight.balls, *events))
    with pytest.raises(IllegalActionError) as err:
        eight.check_shot(0)
    assert err.value.code == "call_required"
    for bad in (6, -1, True, 1.0):
        with pytest.raises(IllegalActionError) as err:
            eight.call_pocket(0, bad)
        assert err.value.code == "bad_pocket"
    eight.call_pocket(0, 5)
    assert eight.called_pocket == 5 and eight.public_state()["called_pocket"] == 5
    eight.check_shot(0)


def test_real_eight_in_the_called_pocket_wins(eight: Game) -> None:
    clear_solids(eight)
    placement, shot = straight_in(8, pocket=0)
    arrange(eight, placement)
    eight.call_pocket(0, 0)
    outcome = eight.apply(0, simulate(TABLE, eight.balls, shot))
    assert outcome.frame_over and outcome.winner == 0 and eight.over
    assert outcome.message == (
        "Ana pocketed the 8. Ana pocketed the 8 in the called bottom "
        "left pocket. Ana wins the game."
    )
    with pytest.raises(IllegalActionError) as err:
        eight.check_shot(1)
    assert err.value.code == "game_over"


def test_real_eight_in_an_uncalled_pocket_loses(eight: Game) -> None:
    clear_solids(eight)
    placement, shot = straight_in(8, pocket=0)
    arrange(eight, placement)
    eight.call_pocket(0, 5)
    outcome = eight.apply(0, simulate(TABLE, eight.balls, shot))
    assert outcome.winner == 1
    assert outcome.reason == (
        "Ana pocketed the 8 in the bottom left pocket, not the called top left pocket."
    )


def test_eight_before_the_group_is_cleared_loses(eight: Game) -> None:
    solids_for_ana(eight)
    outcome = eight.apply(0, crafted(eight.balls, hit(0, 3), hit(3, 8), pot(8, 0)))
    assert outcome.winner == 1 and outcome.reason == (
        "Ana pocketed the 8 before clearing the solids."
    )


def test_eight_on_an_open_table_after_the_break_loses(eight: Game) -> None:
    legal_break_pocketing(eight)
    outcome = eight.apply(0, crafted(eight.balls, hit(0, 3), hit(3, 8), pot(8, 0)))
    assert outcome.winner == 1


def test_eight_with_the_last_group_ball_loses(eight: Game) -> None:
    solids_for_ana(eight)
    eight.apply(0, crafted(eight.balls, hit(0, 3), pot(3, 1), pot(4, 1), pot(5, 1), pot(6, 1)))
    outcome = eight.apply(0, crafted(eight.balls, hit(0, 7), pot(7, 1), pot(8, 0)))
    assert outcome.winner == 1


def test_scratch_while_pocketing_the_eight_loses(eight: Game) -> None:
    clear_solids(eight)
    eight.call_pocket(0, 0)
    outcome = eight.apply(0, crafted(eight.balls, hit(0, 8), pot(8, 0), pot(0, 2)))
    assert outcome.winner == 1 and outcome.reason == "Ana scratched while pocketing the 8."


def test_foul_on_the_eight_without_pocketing_it_is_only_a_foul(eight: Game) -> None:
    clear_solids(eight)
    eight.call_pocket(0, 0)
    outcome = eight.apply(0, crafted(eight.balls, hit(0, 8), rail(8), pot(0, 2)))
    assert not outcome.frame_over and [f.code for f in outcome.fouls] == ["scratch"]
    assert eight.turn == 1 and eight.called_pocket is None


def test_on_the_eight_hitting_another_ball_first_is_a_foul(eight: Game) -> None:
    clear_solids(eight)
    eight.call_pocket(0, 0)
    outcome = eight.apply(0, crafted(eight.balls, hit(0, 9), rail(9)))
    assert outcome.fouls[0].message.endswith("must be the 8.")
