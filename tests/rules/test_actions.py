"""Actions out of turn or at the wrong time raise a named error and change nothing."""

from __future__ import annotations

import json

import pytest

from server.rules import Game, IllegalActionError

from .helpers import TABLE, crafted, hit, pot, rail


def state(game: Game) -> str:
    return json.dumps(game.public_state(), sort_keys=True)


@pytest.mark.parametrize(
    "action",
    [
        lambda g: g.check_shot(1),
        lambda g: g.check_shot(5),
        lambda g: g.place_cue(1, 0.5, 0.5),
        lambda g: g.call_pocket(1, 0),
        lambda g: g.declare_push_out(1),
        lambda g: g.timeout(1),
        lambda g: g.apply(1, crafted(g.balls, hit(0, 1))),
    ],
)
def test_out_of_turn(action) -> None:
    game = Game.new("nine_ball", ("Ana", "Bob"), table=TABLE)
    before = state(game)
    with pytest.raises(IllegalActionError) as err:
        action(game)
    assert err.value.code == "not_your_turn" and err.value.message
    assert state(game) == before


def test_a_result_from_another_table_is_refused() -> None:
    nine = Game.new("nine_ball", ("Ana", "Bob"), table=TABLE)
    eight = Game.new("eight_ball", ("Ana", "Bob"), table=TABLE)
    with pytest.raises(IllegalActionError) as err:
        nine.apply(0, crafted(eight.balls, hit(0, 1)))
    assert err.value.code == "bad_result"


def test_timeout_on_the_break_passes_the_break() -> None:
    game = Game.new("eight_ball", ("Ana", "Bob"), table=TABLE)
    outcome = game.timeout(0)
    assert [f.code for f in outcome.fouls] == ["shot_clock"]
    assert game.breaking and game.turn == 1 and game.breaker == 1
    assert game.ball_in_hand == "behind_head_string"
    assert outcome.message == (
        "Foul: time ran out. Bob breaks instead. Ball in hand behind the head string for Bob."
    )


def test_timeout_during_a_decision_takes_the_first_option() -> None:
    game = Game.new("eight_ball", ("Ana", "Bob"), table=TABLE)
    game.apply(0, crafted(game.balls, hit(0, 1), rail(2)))  # illegal break
    outcome = game.timeout(1)
    assert outcome.fouls == () and game.decision is None and game.turn == 1
    assert outcome.message == "Time ran out. Bob accepts the table and shoots."


def test_game_over_blocks_everything() -> None:
    game = Game.new("nine_ball", ("Ana", "Bob"), table=TABLE)
    game.apply(0, crafted(game.balls, hit(0, 1), pot(9, 0)))
    before = state(game)
    for action in (
        lambda: game.check_shot(0),
        lambda: game.timeout(0),
        lambda: game.place_cue(0, 0.5, 0.5),
        lambda: game.resign(1, "x"),
    ):
        with pytest.raises(IllegalActionError) as err:
            action()
        assert err.value.code == "game_over"
    assert state(game) == before
