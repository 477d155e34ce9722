"""Whole games to the end, played with real engine shots from scripted positions.

Each scripted shot sets the balls up (`arrange`) and plays a real straight-in shot through
`simulate`; the break is a real break from the rack. Decisions take their first option.
"""

from __future__ import annotations

import math

from server.engine import Shot, simulate
from server.rules import Game, Match

from .helpers import TABLE, arrange, straight_in

SCRATCH = "scratch"
POT = "pot"


def play(game: Game, seat: int, plan: str) -> None:
    """One scripted shot for `seat`: pot the first legal ball in the bottom-left pocket, or
    scratch (the cue ball straight into that pocket, touching nothing)."""
    while game.decision is not None:
        game.decide(game.decision.seat, game.decision.options[0])
    assert game.turn == seat
    target = game.legal_targets()[0]
    placement, shot = straight_in(target, pocket=0)
    if plan == SCRATCH:
        placement = {0: placement[target]}
    cue = placement.pop(0)
    arrange(game, placement if game.ball_in_hand else {**placement, 0: cue})
    if game.ball_in_hand:
        game.place_cue(seat, *cue)
    if game.requires_call:
        game.call_pocket(seat, 0)
    game.check_shot(seat)
    game.apply(seat, simulate(TABLE, game.balls, shot))


def real_break(game: Game, seat: int) -> None:
    game.place_cue(seat, TABLE.head_string, TABLE.width / 2 + 0.05)
    fx, fy = TABLE.foot_spot
    angle = math.atan2(fy - (TABLE.width / 2 + 0.05), fx - TABLE.head_string)
    game.apply(seat, simulate(TABLE, game.balls, Shot(angle, 9.0)))


def test_full_eight_ball_game() -> None:
    game = Game.new("eight_ball", ("Ana", "Bob"), seed=3, table=TABLE)
    real_break(game, 0)
    while game.decision is not None:
        game.decide(game.decision.seat, game.decision.options[0])
    shooter = game.turn
    play(game, shooter, POT)  # decides the groups
    assert game.groups is not None and game.turn == shooter
    play(game, shooter, SCRATCH)
    assert game.turn == 1 - shooter and game.ball_in_hand == "anywhere"
    runner = game.turn
    shots = 0
    while not game.over:
        assert game.turn == runner
        play(game, runner, POT)
        shots += 1
        assert shots < 20
    assert game.winner == runner
    assert game.reason.endswith("in the called bottom left pocket.")
    own = game.groups[runner]
    assert game.balls_left()[runner] == [] and 8 not in game.balls.on_table_ids()
    assert own in ("solids", "stripes")


def test_full_eight_ball_game_through_match() -> None:
    match = Match("eight_ball", ("Ana", "Bob"), race_to=1, seed=5, table=TABLE)
    game = match.game
    real_break(game, 0)
    while not game.over:
        while game.decision is not None:
            game.decide(game.decision.seat, game.decision.options[0])
        seat = game.turn
        target = game.legal_targets()[0]
        placement, shot = straight_in(target, pocket=0)
        cue = placement.pop(0)
        arrange(game, placement if game.ball_in_hand else {**placement, 0: cue})
        if game.ball_in_hand:
            game.place_cue(seat, *cue)
        if game.requires_call:
            game.call_pocket(seat, 0)
        match.apply(seat, simulate(TABLE, game.balls, shot))
    assert match.over and match.winner == game.winner and match.score[game.winner] == 1


def test_full_nine_ball_game_with_push_out_and_foul() -> None:
    game = Game.new("nine_ball", ("Ana", "Bob"), seed=2, table=TABLE)
    real_break(game, 0)
    assert game.push_out_available
    pusher = game.turn
    game.declare_push_out(pusher)
    cue = game.balls.position_of(0)
    game.apply(
        pusher,
        simulate(TABLE, game.balls, Shot(math.pi / 2 if cue[1] < 0.6 else -math.pi / 2, 0.5)),
    )
    assert game.decision is not None and game.decision.options == ("shoot", "pass")
    taker = 1 - pusher
    game.decide(taker, "shoot")
    assert game.turn == taker
    play(game, taker, POT)
    assert game.turn == taker
    play(game, taker, SCRATCH)
    assert game.turn == pusher and game.fouls_in_row[taker] == 1
    shots = 0
    while not game.over:
        lowest = game.legal_targets()[0]
        play(game, pusher, POT)
        assert lowest not in game.balls.on_table_ids()
        shots += 1
        assert shots < 12
    assert game.winner == pusher and game.balls.on_table_ids() == [0]
    assert game.reason == f"{game.players[pusher]} pocketed the 9."
