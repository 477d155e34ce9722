"""The computer at three-cushion: it finds points with the engine, strikes its own cue
ball, respects the opening, and plans the same turn for the same position."""

from dataclasses import replace

import numpy as np
import pytest

from server.ai import Bot
from server.ai.carom import leave_value
from server.ai.play import play_turn
from server.engine import BallSet, Table, simulate
from server.engine.rack import RED, WHITE, YELLOW
from server.rules import Game
from server.rules.carom_score import is_point
from server.rules.shotfacts import shot_facts

CAROM = Table.carom()


def after_opening(balls: BallSet, turn: int = 0) -> Game:
    game = Game.new("three_cushion", ("Ana", "Ben"))
    assert game.carom is not None
    game.carom = replace(game.carom, opening=False)
    game.turn = turn
    game.balls = balls
    return game


OPEN = BallSet.place({WHITE: (0.8, 0.4), YELLOW: (1.9, 1.0), RED: (1.5, 0.3)})


@pytest.mark.parametrize("level", ["amateur", "pro"])
def test_the_plan_scores_when_played_exactly(level):
    game = after_opening(OPEN)
    turn = Bot(level).plan(game, 0)
    assert turn.shot is not None and turn.shot.ball == WHITE and turn.kind == "point"
    result = simulate(CAROM, OPEN, turn.shot)
    assert is_point(shot_facts(OPEN, result, WHITE).cue_path, WHITE)


def test_the_yellow_is_struck_on_the_second_players_turn():
    game = after_opening(OPEN, turn=1)
    turn = Bot("club").plan(game, 1)
    assert turn.shot is not None and turn.shot.ball == YELLOW
    outcome, _ = play_turn(game, 1, turn)
    assert outcome is not None and outcome.shooter == 1


def test_the_opening_stroke_is_played_on_the_red_first():
    game = Game.new("three_cushion", ("Ana", "Ben"))
    turn = Bot("pro").plan(game, 0)
    assert turn.target == RED and turn.shot is not None
    path = shot_facts(game.balls, simulate(CAROM, game.balls, turn.shot)).cue_path
    assert path[0] == RED


def test_the_same_position_gets_the_same_plan_and_the_noise_keeps_the_ball():
    game = after_opening(OPEN, turn=1)
    assert Bot("amateur", 3).plan(game, 1) == Bot("amateur", 3).plan(game, 1)
    shot = Bot("amateur").plan(game, 1).shot
    assert shot is not None
    played = Bot("pro").execute(shot, np.random.default_rng(0), CAROM)
    assert played.ball == YELLOW and played != shot


def test_a_leave_with_the_balls_apart_and_on_a_rail_is_worth_less():
    easy = BallSet.place({WHITE: (1.0, 0.7), YELLOW: (1.2, 0.7), RED: (1.1, 0.75)})
    hard = BallSet.place({WHITE: (0.1, 0.1), YELLOW: (2.8, 0.7), RED: (2.7, 1.3)})
    assert leave_value(CAROM, hard, WHITE) < leave_value(CAROM, easy, WHITE)


def test_show_me_a_shot_on_the_three_cushion_practice_table():
    # The hint is the top level's plan: on the opening, a point off the red first.
    game = Game.new("three_cushion_practice", ("Pia",))
    turn = Bot("pro", seed=1).plan(game, 0)
    assert turn.shot is not None and turn.kind == "point" and turn.target == RED
    out, _ = play_turn(game, 0, turn)
    assert out is not None and not out.fouls and game.turn == 0 and game.points == (1,)
