"""`Game`/`Match` `to_dict`/`from_dict`: a stored game comes back exactly and plays on the same.

The server saves rooms after every shot (restart recovery); these prove nothing is lost.
"""

from __future__ import annotations

import json
import math

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from server.engine import Shot, simulate
from server.rules import Game, Match, Outcome

from .helpers import TABLE
from .test_properties import act, check_possible


def through_json(data: dict) -> dict:
    return json.loads(json.dumps(data, allow_nan=False))


def same_game(a: Game, b: Game) -> None:
    assert set(vars(a)) == set(vars(b))  # a new attribute must be stored too
    assert a.to_dict() == b.to_dict()
    assert a.public_state() == b.public_state()
    assert a.balls.positions.tobytes() == b.balls.positions.tobytes()


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(kind=st.sampled_from(["eight_ball", "nine_ball", "practice"]),
       seed=st.integers(0, 5), data=st.data())
def test_a_restored_game_is_identical_and_keeps_playing(kind, seed, data) -> None:
    players = ("Ana",) if kind == "practice" else ("Ana", "Bob")
    game = Game(kind, players, table=TABLE, seed=seed)
    for _ in range(30):
        if game.over:
            break
        restored = Game.from_dict(through_json(game.to_dict()))
        same_game(game, restored)
        game = restored  # play on from the stored copy
        act(data, game)
        check_possible(game)


SHOTS = [Shot(0.0, 9.0), Shot(0.3, 3.0, (0.1, 0.2)), Shot(2.5, 4.0), Shot(-1.2, 5.5),
         Shot(1.0, 2.0, (-0.2, 0.0)), Shot(math.pi, 6.0), Shot(0.7, 7.0), Shot(-2.8, 3.5)]


def play(match: Match, restore_each_time: bool) -> tuple[Match, list[Outcome]]:
    outcomes = []
    for shot in SHOTS:
        if match.over:
            break
        if restore_each_time:
            match = Match.from_dict(through_json(match.to_dict()))
        game = match.game
        if game.decision is not None:
            game.decide(game.decision.seat, game.decision.options[0])
        seat = game.turn
        if not game.balls.on_table[game.balls.index(0)]:
            game.place_cue(seat, *TABLE.head_spot)
        if game.requires_call:
            game.call_pocket(seat, 0)
        game.check_shot(seat)
        outcomes.append(match.apply(seat, simulate(game.table, game.balls, shot)))
        if match.game.over and not match.over:
            match.next_game()
    return match, outcomes


def test_a_match_restored_before_every_shot_ends_exactly_like_one_never_stored() -> None:
    for kind in ("eight_ball", "nine_ball"):
        straight, outcomes = play(Match(kind, ("Ana", "Bob"), race_to=3, seed=4), False)
        stored, stored_outcomes = play(Match(kind, ("Ana", "Bob"), race_to=3, seed=4), True)
        assert outcomes == stored_outcomes
        assert len(outcomes) >= 4
        assert straight.to_dict() == stored.to_dict()
        assert set(vars(straight)) == set(vars(stored))
        same_game(straight.game, stored.game)


def test_match_round_trip_keeps_score_winner_and_rematch() -> None:
    match = Match("eight_ball", ("Ana", "Bob"), race_to=2, seed=9)
    match.concede(0)
    match.next_game()
    match.concede(0)
    assert match.over and match.winner == 1
    restored = Match.from_dict(through_json(match.to_dict()))
    assert restored.to_dict() == match.to_dict()
    assert restored.public_state() == match.public_state()
    assert (restored.score, restored.winner, restored.reason) == ([0, 2], 1, match.reason)
    restored.rematch()
    match.rematch()
    assert restored.to_dict() == match.to_dict() and restored.first_breaker == 1


def test_outcome_round_trip() -> None:
    match = Match("nine_ball", ("Ana", "Bob"), seed=1)
    outcome = match.timeout(0)
    assert outcome.fouls
    assert Outcome.from_dict(through_json(outcome.to_dict())) == outcome
