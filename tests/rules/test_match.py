"""Match: race to N, alternating break, concede, forfeit, rematch."""

from __future__ import annotations

import json

import pytest

from server.rules import IllegalActionError, Match

from .helpers import TABLE, crafted, hit, pot


def win_on_the_break(match: Match) -> None:
    """The breaker pockets the 9 on the break: a quick 9-ball game."""
    game = match.game
    match.apply(game.turn, crafted(game.balls, hit(0, 1), pot(9, 2)))


def test_race_to_two_with_alternating_break() -> None:
    match = Match("nine_ball", ("Ana", "Bob"), race_to=2, table=TABLE)
    assert match.game.breaker == 0
    win_on_the_break(match)
    assert match.score == [1, 0] and not match.over
    assert match.game.last_outcome.message.endswith("Score 1-0.")
    with pytest.raises(IllegalActionError) as err:
        match.apply(1, crafted(match.game.balls))
    assert err.value.code == "game_over"
    match.next_game()
    assert match.game.breaker == 1 and match.game.turn == 1
    win_on_the_break(match)
    assert match.score == [1, 1]
    match.next_game()
    assert match.game.breaker == 0
    outcome = match.game
    win_on_the_break(match)
    assert match.over and match.winner == 0 and match.score == [2, 1]
    assert outcome.last_outcome.message.endswith("Ana wins the match 2-1.")
    with pytest.raises(IllegalActionError) as err:
        match.next_game()
    assert err.value.code == "match_over"


def test_next_game_only_after_a_game_ends() -> None:
    match = Match("eight_ball", ("Ana", "Bob"), race_to=3, table=TABLE)
    with pytest.raises(IllegalActionError) as err:
        match.next_game()
    assert err.value.code == "game_not_over"


def test_concede_loses_the_current_game() -> None:
    match = Match("eight_ball", ("Ana", "Bob"), race_to=2, table=TABLE)
    outcome = match.concede(1)
    assert outcome.frame_over and outcome.winner == 0 and match.score == [1, 0]
    assert outcome.reason == "Bob conceded the game."
    assert not match.over


def test_forfeit_loses_the_match() -> None:
    match = Match("eight_ball", ("Ana", "Bob"), race_to=5, table=TABLE)
    outcome = match.forfeit(0, "Ana left and did not come back.")
    assert match.over and match.winner == 1
    assert outcome.message.startswith("Ana left and did not come back.")
    assert match.public_state()["match_reason"] == "Ana left and did not come back."


def test_forfeit_game_loses_only_the_frame_until_the_race_is_over() -> None:
    match = Match("eight_ball", ("Ana", "Bob"), race_to=2, table=TABLE)
    outcome = match.forfeit_game(0, "Ana left the table and did not come back.")
    assert outcome.frame_over and outcome.winner == 1 and match.score == [0, 1]
    assert not match.over and outcome.message.startswith("Ana left the table")
    match.next_game()
    match.forfeit_game(0, "Ana left the table and did not come back.")
    assert match.over and match.winner == 1 and match.score == [0, 2]


def test_forfeit_between_games() -> None:
    match = Match("eight_ball", ("Ana", "Bob"), race_to=5, table=TABLE)
    match.concede(1)
    match.forfeit(1, "Bob left.")
    assert match.over and match.winner == 0 and match.score == [1, 0]


def test_rematch_starts_again_at_zero_with_the_other_breaker() -> None:
    match = Match("nine_ball", ("Ana", "Bob"), race_to=1, table=TABLE)
    win_on_the_break(match)
    assert match.over
    match.rematch()
    assert not match.over and match.score == [0, 0] and match.winner is None
    assert match.game.breaker == 1 and not match.game.over


def test_public_state_is_json_and_shows_the_score() -> None:
    match = Match("eight_ball", ("Ana", "Bob"), race_to=3, table=TABLE)
    match.concede(0)
    state = json.loads(json.dumps(match.public_state()))
    assert state["score"] == [0, 1] and state["race_to"] == 3
    assert state["winner"] == 1 and state["over"] is True and state["match_over"] is False
    assert state["last_outcome"]["reason"] == "Ana conceded the game."
    assert len(state["balls"]) == 16


def test_bad_race_is_refused() -> None:
    with pytest.raises(ValueError):
        Match("eight_ball", ("Ana", "Bob"), race_to=0)
