"""The pro level's swerves and masses: when the straight path to a legal ball is blocked
by a ball a jump cannot clear (too far from the cue ball), it also tries curving the cue
ball round it with a raised cue and side spin (`Search.curve_candidates`)."""

from __future__ import annotations

from server.ai import Bot
from server.engine import Shot, simulate
from server.rules import Game
from server.rules.shotfacts import shot_facts

from .conftest import TABLE, set_table

# 9-ball: the 1 straight ahead of the cue ball, the 2 in the way 50 cm ahead (beyond a
# jump's 35 cm), the 9 off the line.
FAR = {0: (0.6, 0.6), 2: (1.1, 0.6), 1: (1.6, 0.6), 9: (2.2, 1.0)}
CLEAR = {0: (0.6, 0.6), 2: (1.1, 0.9), 1: (1.6, 0.6), 9: (2.2, 1.0)}


def test_a_far_blocker_gets_curves_both_ways_and_no_jump(nine: Game) -> None:
    game = set_table(nine, FAR)
    search = Bot("pro")._search(game, 0)
    assert search.jump_candidates(game.balls) == []
    curves = search.curve_candidates(game.balls)
    assert curves and all(c.shot.elevation > 0 and c.target == 1 for c in curves)
    # Right spin (curving right) is aimed left of the line, left spin right of it.
    assert all((c.shot.tip[0] > 0) == (c.shot.angle > 0) for c in curves)
    hits = [
        shot_facts(game.balls, simulate(TABLE, game.balls, c.shot)).first_contact for c in curves
    ]
    assert 1 in hits, hits
    level = simulate(TABLE, game.balls, Shot(0.0, 2.5))
    assert shot_facts(game.balls, level).first_contact == 2  # level, the 2 is hit first


def test_no_curve_when_the_path_is_clear_or_below_the_pro_level(nine: Game) -> None:
    game = set_table(nine, CLEAR)
    assert Bot("pro")._search(game, 0).curve_candidates(game.balls) == []
    game = set_table(nine, FAR)
    assert Bot("club")._search(game, 0).curve_candidates(game.balls) == []


def test_the_pro_curves_round_a_ball_too_far_to_jump(nine: Game) -> None:
    # The engine's masse at 60 degrees and 2 m/s bends the ball 58 cm over 1 m
    # (docs/engine.md): enough to come back round the 2 and hit the 1 first.
    game = set_table(nine, FAR)
    turn = Bot("pro").plan(game, 0)
    assert turn.shot is not None and turn.shot.elevation > 0 and turn.shot.tip[0] != 0
    facts = shot_facts(game.balls, simulate(TABLE, game.balls, turn.shot))
    assert facts.first_contact == 1
