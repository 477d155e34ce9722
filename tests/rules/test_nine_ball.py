"""WPA 9-ball, one test per rule."""

from __future__ import annotations

import pytest

from server.engine import simulate
from server.rules import ANYWHERE, Game, IllegalActionError

from .helpers import TABLE, arrange, crafted, hit, pot, rail, straight_in

FOUR_RAILS = [rail(2), rail(3), rail(4), rail(5)]


def legal_break(game: Game) -> None:
    """Ana breaks legally and pockets nothing: Bob to shoot, push out available."""
    game.apply(0, crafted(game.balls, hit(0, 1), *FOUR_RAILS))
    assert game.turn == 1 and game.push_out_available


def test_break_must_hit_the_one_first(nine: Game) -> None:
    outcome = nine.apply(0, crafted(nine.balls, hit(0, 2), *FOUR_RAILS))
    assert [f.code for f in outcome.fouls] == ["wrong_ball_first"]
    assert outcome.next_turn == 1 and outcome.ball_in_hand == ANYWHERE


def test_break_needs_a_ball_pocketed_or_four_to_a_rail(nine: Game) -> None:
    outcome = nine.apply(0, crafted(nine.balls, hit(0, 1), rail(2), rail(3), rail(4)))
    assert [f.code for f in outcome.fouls] == ["illegal_break"]
    assert outcome.ball_in_hand == ANYWHERE and nine.decision is None


def test_break_pocketing_a_ball_continues(nine: Game) -> None:
    outcome = nine.apply(0, crafted(nine.balls, hit(0, 1), pot(5, 2)))
    assert outcome.fouls == () and outcome.continues and nine.push_out_available
    assert outcome.message == "Ana pocketed the 5. Ana shoots again. Ana may play a push out."


def test_nine_on_the_break_wins(nine: Game) -> None:
    outcome = nine.apply(0, crafted(nine.balls, hit(0, 1), pot(9, 3)))
    assert outcome.winner == 0 and outcome.reason == "Ana pocketed the 9 on the break."


def test_nine_on_a_foul_break_is_spotted(nine: Game) -> None:
    outcome = nine.apply(0, crafted(nine.balls, hit(0, 1), pot(9, 3), pot(0, 0)))
    assert not outcome.frame_over and outcome.spotted == (9,)
    assert 9 in nine.balls.on_table_ids() and nine.turn == 1
    assert "The 9 is spotted." in outcome.message


def test_lowest_ball_must_be_hit_first(nine: Game) -> None:
    legal_break(nine)
    outcome = nine.apply(1, crafted(nine.balls, hit(0, 3), rail(3)))
    assert [f.code for f in outcome.fouls] == ["wrong_ball_first"]
    assert outcome.fouls[0].message == "Bob hit the 3 first; the first ball hit must be the 1."


def test_rail_after_contact_is_required(nine: Game) -> None:
    legal_break(nine)
    outcome = nine.apply(1, crafted(nine.balls, hit(0, 1)))
    assert [f.code for f in outcome.fouls] == ["no_rail"]


def test_any_ball_pocketed_on_a_legal_shot_counts(nine: Game) -> None:
    legal_break(nine)
    outcome = nine.apply(1, crafted(nine.balls, hit(0, 1), hit(1, 6), pot(6, 4)))
    assert outcome.fouls == () and outcome.continues and nine.turn == 1


def test_real_pot_of_the_nine_as_the_last_ball_wins(nine: Game) -> None:
    legal_break(nine)
    for ball in range(1, 9):  # the 1 to the 8 are gone: pocketed on a legal shot each
        nine.apply(1, crafted(nine.balls, hit(0, ball), pot(ball, 2)))
    assert nine.balls.on_table_ids() == [0, 9]
    placement, shot = straight_in(9, pocket=0)
    arrange(nine, placement)
    outcome = nine.apply(1, simulate(TABLE, nine.balls, shot))
    assert outcome.winner == 1 and outcome.reason == "Bob pocketed the 9."


def test_combination_nine_wins(nine: Game) -> None:
    legal_break(nine)
    outcome = nine.apply(1, crafted(nine.balls, hit(0, 1), hit(1, 9), pot(9, 5)))
    assert outcome.winner == 1 and outcome.reason == "Bob pocketed the 9 in a combination."


def test_illegally_pocketed_nine_is_respotted(nine: Game) -> None:
    legal_break(nine)
    outcome = nine.apply(1, crafted(nine.balls, hit(0, 2), hit(2, 9), pot(9, 5)))
    assert not outcome.frame_over and outcome.spotted == (9,)
    assert 9 in outcome.pocketed and 9 in nine.balls.on_table_ids()


def test_push_out_only_on_the_shot_after_the_break(nine: Game) -> None:
    with pytest.raises(IllegalActionError) as err:
        nine.declare_push_out(0)
    assert err.value.code == "push_out_not_allowed"
    legal_break(nine)
    with pytest.raises(IllegalActionError) as err:
        nine.declare_push_out(0)
    assert err.value.code == "not_your_turn"
    nine.declare_push_out(1)
    # no ball need be hit first, no rail needed; a ball pocketed stays down
    outcome = nine.apply(1, crafted(nine.balls, hit(0, 7), pot(7, 1)))
    assert outcome.fouls == ()
    assert nine.decision is not None and nine.decision.seat == 0
    assert nine.decision.options == ("shoot", "pass")
    nine.decide(0, "pass")
    assert nine.turn == 1 and nine.ball_in_hand is None
    with pytest.raises(IllegalActionError) as err:
        nine.declare_push_out(1)
    assert err.value.code == "push_out_not_allowed"


def test_push_out_accepted_shoot(nine: Game) -> None:
    legal_break(nine)
    nine.declare_push_out(1)
    nine.apply(1, crafted(nine.balls))
    with pytest.raises(IllegalActionError) as err:
        nine.decide(0, "later")
    assert err.value.code == "bad_option"
    with pytest.raises(IllegalActionError) as err:
        nine.decide(1, "shoot")
    assert err.value.code == "not_your_turn"
    nine.decide(0, "shoot")
    assert nine.turn == 0 and nine.decision is None
    with pytest.raises(IllegalActionError) as err:
        nine.decide(0, "shoot")
    assert err.value.code == "no_decision"


def test_push_out_scratch_is_a_foul_and_nine_spotted(nine: Game) -> None:
    legal_break(nine)
    nine.declare_push_out(1)
    outcome = nine.apply(1, crafted(nine.balls, hit(0, 9), pot(9, 1), pot(0, 2)))
    assert [f.code for f in outcome.fouls] == ["scratch"] and nine.decision is None
    assert 9 in nine.balls.on_table_ids() and outcome.ball_in_hand == ANYWHERE


def test_three_consecutive_fouls_lose(nine: Game) -> None:
    legal_break(nine)
    for k in range(2):
        outcome = nine.apply(1, crafted(nine.balls, rail(0)))  # Bob: no contact
        assert not outcome.frame_over
        nine.place_cue(0, 0.5, 0.5)
        nine.apply(0, crafted(nine.balls, hit(0, 1), rail(1)))  # Ana: legal, misses
        assert nine.fouls_in_row == [0, k + 1]
    outcome = nine.apply(1, crafted(nine.balls, rail(0)))
    assert outcome.winner == 0 and outcome.reason == "Bob fouled three times in a row."


def test_two_fouls_warn_and_a_legal_shot_resets_the_count(nine: Game) -> None:
    legal_break(nine)
    nine.apply(1, crafted(nine.balls, rail(0)))
    nine.apply(0, crafted(nine.balls, hit(0, 1), rail(1)))
    outcome = nine.apply(1, crafted(nine.balls, rail(0)))
    assert "Bob is on two fouls: a third foul in a row loses." in outcome.message
    nine.apply(0, crafted(nine.balls, hit(0, 1), rail(1)))
    nine.apply(1, crafted(nine.balls, hit(0, 1), rail(1)))
    assert nine.fouls_in_row == [0, 0]


def test_timeouts_count_as_fouls(nine: Game) -> None:
    legal_break(nine)
    for _ in range(2):
        outcome = nine.timeout(1)
        assert [f.code for f in outcome.fouls] == ["shot_clock"] and nine.turn == 0
        nine.apply(0, crafted(nine.balls, hit(0, 1), rail(1)))
    outcome = nine.timeout(1)
    assert outcome.winner == 0
