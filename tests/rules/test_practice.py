"""Practice: one player, ball in hand at will, no fouls, never over."""

from __future__ import annotations

import pytest

from server.engine import simulate
from server.rules import Game, IllegalActionError

from .helpers import TABLE, arrange, crafted, hit, pot, straight_in


def test_practice_is_one_player_with_ball_in_hand_anywhere() -> None:
    game = Game.new("practice", ("Ana",), table=TABLE)
    assert game.turn == 0 and game.ball_in_hand == "anywhere" and not game.breaking
    game.place_cue(0, 2.2, 0.3)  # past the head string: anywhere
    with pytest.raises(IllegalActionError) as err:
        game.check_shot(1)
    assert err.value.code == "not_your_turn"
    with pytest.raises(ValueError):
        Game.new("practice", ("Ana", "Bob"))


def test_practice_has_no_fouls_and_the_cue_ball_comes_back_in_hand() -> None:
    game = Game.new("practice", ("Ana",), table=TABLE)
    outcome = game.apply(0, crafted(game.balls, hit(0, 8), pot(8, 1), pot(0, 2)))
    assert outcome.fouls == () and outcome.next_turn == 0 and not game.over
    assert outcome.ball_in_hand == "anywhere"
    assert outcome.message == "Ana pocketed the 8. The cue ball went in: place it anywhere."
    with pytest.raises(IllegalActionError) as err:
        game.check_shot(0)
    assert err.value.code == "cue_ball_off_table"
    game.place_cue(0, 0.6, 0.6)
    game.check_shot(0)


def test_practice_real_shot_and_rerack() -> None:
    game = Game.new("practice", ("Ana",), table=TABLE)
    placement, shot = straight_in(5, pocket=0)
    arrange(game, placement)
    outcome = game.apply(0, simulate(TABLE, game.balls, shot))
    assert outcome.pocketed == (5,)
    game.rerack()
    assert len(game.balls.on_table_ids()) == 16
    eight = Game.new("eight_ball", ("Ana", "Bob"))
    with pytest.raises(IllegalActionError) as err:
        eight.rerack()
    assert err.value.code == "practice_only"


def test_practice_clearing_the_table_says_so() -> None:
    game = Game.new("practice", ("Ana",), table=TABLE)
    events = [hit(0, 1)] + [pot(b, b % 6) for b in range(1, 16)]
    outcome = game.apply(0, crafted(game.balls, *events))
    assert outcome.message.endswith("Table cleared. Rerack to play again.")
    assert not game.over


def test_a_shot_after_a_rerack_no_longer_shows_the_rerack_notice() -> None:
    """Like every other game, the next outcome replaces the notice (browsers show both)."""
    game = Game.new("practice", ("Ana",), table=TABLE)
    game.rerack()
    assert game.public_state()["notice"] == "Balls re-racked."
    outcome = game.apply(0, crafted(game.balls, hit(0, 1), pot(1, 0)))
    assert outcome.message == "Ana pocketed the 1." and game.notice is None
    game.rerack()
    game.timeout(0)
    assert game.notice is None and game.last_outcome.message == "Time ran out."
